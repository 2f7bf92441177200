#pragma once
// Renders one channel's frustum slice of the dome for a snapshot, into an offscreen RGBA16F
// framebuffer, and reads it back as a linear float image. Needs a current GL 4.5 context.
#include <memory>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "image/frame_image.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

class SceneRenderer {
public:
    SceneRenderer(const ClusterConfig& cluster, const ChannelConfig& channel, const SceneConfig& scene);
    ~SceneRenderer();
    Image render(const Snapshot& snapshot);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace cupola

#pragma once
// A body's surface map with everything the renderer derives from it on the CPU: the decoded image
// (body_texture.hpp), its mipmap chain (image/mip_chain.hpp), its mean colour and its luminance
// grid (planet_light.hpp), tint included. Only the upload to the GPU is left to the body pass.
//
// Prefetch: a slave starts preparing its scene's maps on a worker thread before it makes its GL
// context (prefetch_body_maps), and the body pass takes each prepared map when it gets to it
// (take_body_map), waiting for one that is not ready yet. Decoding the maps then overlaps the
// EGL and driver start-up, which a restarted node's first frame waits for. A map that was not
// prefetched is prepared on the spot; an error while preparing one (a missing file) is thrown
// where the map is taken, as without the prefetch.
#include <glm/glm.hpp>

#include <string>
#include <thread>
#include <vector>

#include "config/scene_config.hpp"
#include "image/mip_chain.hpp"
#include "passes/body_texture.hpp"
#include "passes/planet_light.hpp"

namespace cupola {

struct BodyMap {
    BodyImage image;
    std::vector<MipLevel> mips;  // levels 1.. (level 0 is image)
    glm::dvec3 mean_rgb{0.0};    // body_map_mean_rgb times the tint
    LuminanceGrid grid;          // tint included
};

BodyMap prepare_body_map(const std::string& texture, const glm::dvec3& tint);

// Starts preparing the maps of every body of the scene that has one, in the scene's order, and
// the Milky Way's (passes/milky_way_pass, untinted) on one
// worker thread; each prepared map is held until it is taken. The returned thread must be joined;
// it ends when every map is prepared.
std::thread prefetch_body_maps(const SceneConfig& scene);

// The prefetched map for (texture, tint), taken out of the prefetch (a second call prepares it
// again), or prepared now when none was prefetched.
BodyMap take_body_map(const std::string& texture, const glm::dvec3& tint);

}  // namespace cupola

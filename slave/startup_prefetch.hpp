#pragma once
// The CPU work of a slave's start-up that needs no GL context, started on a worker thread before
// the context is made: the scene's body maps (passes/body_map.hpp: decoded, mipmapped, their
// means and luminance grids). The body pass built after the context takes what is ready and waits
// for what is not, so the work overlaps the EGL and driver start-up that a restarted node's first
// frame waits for. The destructor joins the worker.
#include <thread>

#include "config/scene_config.hpp"

namespace cupola {

class StartupPrefetch {
public:
    explicit StartupPrefetch(const SceneConfig& scene);
    ~StartupPrefetch();
    StartupPrefetch(const StartupPrefetch&) = delete;
    StartupPrefetch& operator=(const StartupPrefetch&) = delete;

private:
    std::thread body_maps_;
};

}  // namespace cupola

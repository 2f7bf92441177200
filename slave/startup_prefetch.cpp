#include "startup_prefetch.hpp"

#include "passes/body_map.hpp"

namespace cupola {

StartupPrefetch::StartupPrefetch(const SceneConfig& scene) : body_maps_(prefetch_body_maps(scene)) {}

StartupPrefetch::~StartupPrefetch() {
    if (body_maps_.joinable()) body_maps_.join();
}

}  // namespace cupola

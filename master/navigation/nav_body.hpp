#pragma once
// What the navigation model needs to know about the scene at one simulation time: each body's
// centre, size and orientation (spheres of radius_m), and the camera pose it produces.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "config/scene_config.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

struct NavBody {
    uint16_t id = 0;  // SceneConfig::bodies index (BodyState::id)
    std::string name;
    double radius_m = 1.0;
    glm::dvec3 position_m{0.0};                  // centre, world frame (metres, origin at the Sun)
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // body frame -> world; body z = north pole
};

// A camera in the world frame: position in metres; orientation maps the camera frame to the world
// (the camera looks along its -Z, +Y is up, +X is right) -- the same convention as the snapshot.
struct CameraPose {
    glm::dvec3 position_m{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
};

// The scene's bodies at the time of `states` (e.g. Snapshot::bodies): one NavBody per state whose
// id names a body of the scene, in the order of `states`.
std::vector<NavBody> nav_bodies(const SceneConfig& scene, const std::vector<BodyState>& states);

}  // namespace cupola

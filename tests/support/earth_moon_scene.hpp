#pragma once
// The earth-moon scene (configs/scenes/earth-moon.json) as the image tests use it, and directions
// in an observer's horizon frame.
#include <glm/glm.hpp>

#include <cmath>

#include "config/scene_config.hpp"
#include "support/test_support.hpp"

namespace cupola::test {

// Loaded once, every body's map generated (no map files needed on the machine).
inline const SceneConfig& earth_moon_scene() {
    static const SceneConfig s = [] {
        SceneConfig c = load_scene_config(source_path("configs/scenes/earth-moon.json"));
        for (auto& b : c.bodies) b.texture = "generated:" + b.name;
        return c;
    }();
    return s;
}

// The unit vector at azimuth az (from north towards east) and elevation el, in degrees: x east,
// y north, z up.
inline glm::dvec3 horizon_direction(double az_deg, double el_deg) {
    const double az = glm::radians(az_deg), el = glm::radians(el_deg);
    return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
}

}  // namespace cupola::test

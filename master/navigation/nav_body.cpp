#include "navigation/nav_body.hpp"

namespace cupola {

std::vector<NavBody> nav_bodies(const SceneConfig& scene, const std::vector<BodyState>& states) {
    std::vector<NavBody> out;
    out.reserve(states.size());
    for (const BodyState& s : states) {
        if (s.id >= scene.bodies.size()) continue;  // not a body of this scene
        const BodyConfig& b = scene.bodies[s.id];
        out.push_back(NavBody{s.id, b.name, b.radius_m, s.position_m, s.orientation});
    }
    return out;
}

}  // namespace cupola

#include "terrain/terrain_clearance.hpp"

#include <glm/gtc/quaternion.hpp>

#include "terrain/body_relief.hpp"

namespace cupola::terrain {

TerrainClearance::TerrainClearance(const SceneConfig& scene, double clearance_m) : clearance_m_(clearance_m) {
    for (const BodyConfig& b : scene.bodies)
        if (b.terrain.present) reliefs_[b.id] = open_body_relief(b).relief;
}

double TerrainClearance::ground_height_m(const BodyState& body, const glm::dvec3& camera_m) const {
    const auto r = reliefs_.find(body.id);
    if (r == reliefs_.end()) return 0.0;
    const glm::dvec3 local = glm::transpose(glm::mat3_cast(body.orientation)) * (camera_m - body.position_m);
    const double d = glm::length(local);
    return d > 0.0 ? r->second->height_m(local / d, 0.0) : 0.0;
}

glm::dvec3 TerrainClearance::on_relief(const BodyState& body, const glm::dvec3& camera_m) const {
    const glm::dvec3 from_centre = camera_m - body.position_m;
    const double d = glm::length(from_centre);
    if (d <= 0.0) return camera_m;
    return camera_m + from_centre / d * ground_height_m(body, camera_m);
}

glm::dvec3 TerrainClearance::keep_above(const std::vector<BodyState>& bodies, const glm::dvec3& camera_m) const {
    glm::dvec3 out = camera_m;
    for (const BodyState& b : bodies) {
        const auto r = reliefs_.find(b.id);
        if (r == reliefs_.end()) continue;
        const glm::dvec3 from_centre = out - b.position_m;
        const double d = glm::length(from_centre);
        const double floor_m = r->second->radius_m() + r->second->max_height_m() + clearance_m_;
        if (d >= floor_m || d <= 0.0) continue;  // above every peak: no look-up
        const double lowest = r->second->radius_m() + ground_height_m(b, out) + clearance_m_;
        if (d >= lowest) continue;
        out = b.position_m + from_centre * (lowest / d);
        ++lifts_;
    }
    return out;
}

}  // namespace cupola::terrain

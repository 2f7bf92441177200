#pragma once
// Keeps the camera above the relief of every body that has terrain: the master applies it to each
// frame's camera (show, live navigation and goto alike), so no channel ever looks from inside a
// mountain. A camera lower than clearance_m above the relief at its place is lifted along the
// body's vertical to that height; one above it is left alone.
#include <glm/glm.hpp>

#include <map>
#include <memory>
#include <vector>

#include "config/scene_config.hpp"
#include "terrain/relief.hpp"
#include "wire/snapshot.hpp"

namespace cupola::terrain {

// How high above the relief the master keeps the camera by default.
constexpr double kGroundClearance_m = 2.0;

class TerrainClearance {
public:
    explicit TerrainClearance(const SceneConfig& scene, double clearance_m = kGroundClearance_m);
    // The camera (world, m) lifted above any relief it is under; bodies: this frame's states.
    glm::dvec3 keep_above(const std::vector<BodyState>& bodies, const glm::dvec3& camera_m) const;
    // A walker's camera, eye_height above the body's sphere, moved along the vertical by the relief's
    // height at its place: the eye then keeps its height above the ground (0 for a body without terrain).
    glm::dvec3 on_relief(const BodyState& body, const glm::dvec3& camera_m) const;
    // The relief's height (m above the body's radius) under a camera, or 0 for a body without terrain.
    double ground_height_m(const BodyState& body, const glm::dvec3& camera_m) const;
    bool any() const { return !reliefs_.empty(); }
    uint64_t lifts() const { return lifts_; }  // frames whose camera was lifted

private:
    std::map<uint16_t, std::shared_ptr<const Relief>> reliefs_;
    double clearance_m_;
    mutable uint64_t lifts_ = 0;
};

}  // namespace cupola::terrain

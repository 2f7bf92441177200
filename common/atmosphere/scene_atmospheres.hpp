#pragma once
// The production atmosphere (CPU, the same shared code the slaves run) of every body that has
// one, built once for the master's own evaluations: the cluster-wide exposure and the glare
// sources' dimming by the air in front of them.
#include <memory>
#include <vector>

#include "atmosphere/production_model.hpp"
#include "config/scene_config.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

class SceneAtmospheres {
public:
    struct Body {
        const BodyConfig* config;
        atmosphere::ProductionAtmosphere model;
    };

    explicit SceneAtmospheres(const SceneConfig& scene);
    const std::vector<std::unique_ptr<Body>>& bodies() const { return bodies_; }
    bool empty() const { return bodies_.empty(); }

    // Transmittance (rgb = the three sample wavelengths, as the atmosphere pass applies it) from
    // the camera along a world direction through every atmosphere of the snapshot, out to space.
    // A ray that ends on a body's ground returns its transmittance to the ground (the body
    // itself hides what lies behind).
    glm::dvec3 transmittance(const Snapshot& snap, const glm::dvec3& direction) const;
    // How much of a star of visual magnitude v_mag the eye sees against the sky behind it, as the
    // slaves' star pass judges it (shaders/shared/star_visibility.glsl): the sky of the atmosphere
    // nearest the camera (by the distance to its top) lit by the Sun `sun` (its state and
    // config), marched here where the slaves look it up in their sky-view table. 1 without an
    // atmosphere, a Sun, or air along the ray; 0 for a ray that meets the ground.
    double star_sky_weight(const Snapshot& snap, const glm::dvec3& direction, double v_mag, const BodyState* sun_state,
                           const BodyConfig* sun) const;

private:
    // The atmosphere nearest the camera by the distance to its top, and its body's state.
    const Body* nearest(const Snapshot& snap, const BodyState** state) const;
    std::vector<std::unique_ptr<Body>> bodies_;
};

}  // namespace cupola

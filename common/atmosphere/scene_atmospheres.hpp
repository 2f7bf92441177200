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

private:
    std::vector<std::unique_ptr<Body>> bodies_;
};

}  // namespace cupola

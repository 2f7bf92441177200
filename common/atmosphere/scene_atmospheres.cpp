#include "atmosphere/scene_atmospheres.hpp"
#include "scene/snapshot_bodies.hpp"

namespace cupola {

SceneAtmospheres::SceneAtmospheres(const SceneConfig& scene) {
    for (const auto& b : scene.bodies)
        if (b.atmosphere.present)
            bodies_.push_back(std::make_unique<Body>(
                Body{&b, atmosphere::ProductionAtmosphere(b.atmosphere.parameters,
                                                          atmosphere::production_quality(b.atmosphere.model))}));
}

glm::dvec3 SceneAtmospheres::transmittance(const Snapshot& snap, const glm::dvec3& direction) const {
    glm::dvec3 t(1.0);
    for (const auto& body : bodies_) {
        const BodyState* st = find_body(snap, body->config->id);
        if (!st) continue;
        const glm::dvec3 to_centre = st->position_m - snap.camera_position_m;
        const double d = glm::length(to_centre);
        if (!(d > 0.0)) continue;
        const glm::dvec3 c_hat = to_centre / d;
        // The sun direction only shapes the in-scatter, which is not wanted here.
        const auto start = shading::atm_ray_start(body->model.shader_params(), static_cast<float>(d),
                                                  glm::vec3(direction), glm::vec3(c_hat), glm::vec3(-c_hat));
        if (!start.valid) continue;
        glm::vec3 tr(1.0f);
        body->model.radiance(start, -1.0f, &tr);
        t *= glm::dvec3(tr);
    }
    return t;
}

}  // namespace cupola

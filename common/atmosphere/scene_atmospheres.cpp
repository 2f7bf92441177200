#include "atmosphere/scene_atmospheres.hpp"

#include <limits>

#include "atmosphere/solar_scale.hpp"
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

const SceneAtmospheres::Body* SceneAtmospheres::nearest(const Snapshot& snap, const BodyState** state) const {
    const Body* best = nullptr;
    double gap = std::numeric_limits<double>::infinity();
    for (const auto& body : bodies_) {
        const BodyState* st = find_body(snap, body->config->id);
        if (!st) continue;
        const double g = glm::length(st->position_m - snap.camera_position_m) - body->model.parameters().top_radius;
        if (g < gap) {
            gap = g;
            best = body.get();
            *state = st;
        }
    }
    return best;
}

double SceneAtmospheres::star_sky_weight(const Snapshot& snap, const glm::dvec3& direction, double v_mag,
                                         const BodyState* sun_state, const BodyConfig* sun) const {
    const BodyState* planet = nullptr;
    const Body* body = nearest(snap, &planet);
    if (!body || !sun_state || !sun || !(sun->radiance > 0.0)) return 1.0;
    const glm::dvec3 to_centre = planet->position_m - snap.camera_position_m;
    const glm::dvec3 to_sun = sun_state->position_m - planet->position_m;
    const double d = glm::length(to_centre), d_sun = glm::length(to_sun);
    if (!(d > 0.0) || !(d_sun > 0.0)) return 1.0;
    const shading::AtmosphereParams& a = body->model.shader_params();
    const auto start = shading::atm_ray_start(a, static_cast<float>(d), glm::vec3(direction), glm::vec3(to_centre / d),
                                              glm::vec3(to_sun / d_sun));
    if (!start.valid) return 1.0;
    if (shading::atm_ray_hits_ground(a, start.r_m, start.mu)) return 0.0;
    glm::vec3 tr(1.0f);
    const double sky = body->model.to_xyz(body->model.radiance(start, -1.0f, &tr)).y;  // cd/m^2 per unit irradiance
    const double to_cd_m2 = atmosphere::sky_to_cd_m2(atmosphere::solar_scale(body->model, *sun, d_sun), sun->radiance);
    const float glow_cd_m2 =
        shading::night_sky_luminance(snap.settings.night_sky_cd_m2, static_cast<float>(d - a.bottom_radius_m),
                                     static_cast<float>(glm::dot(direction, -to_centre / d)));
    return shading::star_sky_weight_over(glm::vec2(static_cast<float>(sky), shading::rec709_luminance(tr)),
                                         static_cast<float>(to_cd_m2), glow_cd_m2, static_cast<float>(v_mag));
}

}  // namespace cupola

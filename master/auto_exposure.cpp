#include "auto_exposure.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/solar_scale.hpp"
#include "projection/dome_frame.hpp"

namespace cupola {

struct AutoExposure::Body {
    const BodyConfig* config;
    atmosphere::ProductionAtmosphere model;
};

AutoExposure::AutoExposure(const ClusterConfig& cluster, const SceneConfig& scene) : cluster_(&cluster), scene_(&scene) {
    if (!cluster.output.auto_exposure.enabled) return;
    for (const auto& b : scene.bodies)
        if (b.atmosphere.present)
            bodies_.push_back(std::make_unique<Body>(
                Body{&b, atmosphere::ProductionAtmosphere(b.atmosphere.parameters,
                                                          atmosphere::production_quality(b.atmosphere.model))}));
}

AutoExposure::~AutoExposure() = default;

double AutoExposure::mean_luminance(const Snapshot& snap) const {
    const BodyState* sun_state = nullptr;
    const BodyConfig* sun = nullptr;
    for (const auto& st : snap.bodies)
        if (st.id < scene_->bodies.size() && scene_->bodies[st.id].kind == BodyKind::Star) {
            sun_state = &st;
            sun = &scene_->bodies[st.id];
            break;
        }
    if (!sun || bodies_.empty()) return 0.0;
    // The dome apex in the world: camera orientation * tilt * +Y.
    const glm::dmat3 cam = glm::mat3_cast(snap.camera_orientation) * dome_tilt_rotation(cluster_->dome.tilt_deg);
    double sum = 0.0;
    for (const auto& body : bodies_) {
        const BodyState* st = nullptr;
        for (const auto& s : snap.bodies)
            if (s.id == body->config->id) st = &s;
        if (!st) continue;
        const glm::dvec3 to_centre = st->position_m - snap.camera_position_m;
        const double d = glm::length(to_centre);
        const glm::dvec3 c_hat = to_centre / d;
        const glm::dvec3 sun_dir = glm::normalize(sun_state->position_m - snap.camera_position_m);
        const double scale = atmosphere::solar_scale(body->model, *sun, glm::length(sun_state->position_m - st->position_m));
        for (int i = 0; i < directions_; ++i) {
            // Fibonacci directions over the hemisphere around the apex (+Y of the dome frame).
            const double y = 1.0 - (i + 0.5) / directions_;
            const double phi = 2.399963229728653 * i;
            const double s = std::sqrt(std::max(0.0, 1.0 - y * y));
            const glm::dvec3 v = cam * glm::dvec3(s * std::cos(phi), y, s * std::sin(phi));
            const auto start = shading::atm_ray_start(body->model.shader_params(), static_cast<float>(d), glm::vec3(v),
                                                      glm::vec3(c_hat), glm::vec3(sun_dir));
            const glm::vec3 f = body->model.radiance(start, -1.0f, nullptr);
            sum += body->model.to_xyz(f).y * scale;
        }
    }
    return sum / directions_;
}

double AutoExposure::exposure(const Snapshot& snap) const {
    const AutoExposureConfig& ae = cluster_->output.auto_exposure;
    if (!ae.enabled) return cluster_->output.exposure;
    const double mean = mean_luminance(snap);
    const double e = mean > 0.0 ? ae.key / mean : ae.max_exposure;
    return std::clamp(e, ae.min_exposure, ae.max_exposure);
}

}  // namespace cupola

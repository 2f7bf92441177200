#include "glare/glare_sources.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "atmosphere/solar_scale.hpp"
#include "glare/analytic_visibility.hpp"
#include "scene/snapshot_bodies.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

namespace {

double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// Lambert sphere phase law, normalised to 1 at full phase.
double lambert_phase(double phase_angle) {
    const double a = std::clamp(phase_angle, 0.0, std::numbers::pi);
    return (std::sin(a) + (std::numbers::pi - a) * std::cos(a)) / std::numbers::pi;
}

// A point source's visibility: hidden when the ray from the camera meets a body first.
bool point_visible(const glm::dvec3& camera, const glm::dvec3& dir, const std::vector<SphereOccluder>& occluders) {
    for (const auto& o : occluders) {
        const glm::dvec3 oc = o.center_m - camera;
        const double along = glm::dot(oc, dir);
        const double d2 = glm::dot(oc, oc);
        if (d2 <= o.radius_m * o.radius_m) return false;  // inside it
        if (along <= 0.0) continue;
        if (d2 - along * along < o.radius_m * o.radius_m) return false;
    }
    return true;
}

}  // namespace

GlareSources::GlareSources(const SceneConfig& scene, const SceneAtmospheres* atmospheres)
    : scene_(&scene), atmospheres_(atmospheres) {
    if (scene.glare.enabled && !scene.stars.catalog.empty())
        stars_ = load_star_catalog(scene.stars.catalog, kCatalogMagnitudeLimit);
}

double GlareSources::display_at_one_degree(const glm::dvec3& irradiance, double exposure) const {
    const float one_degree = static_cast<float>(std::numbers::pi / 180.0);
    const double psf = shading::glare_bloom(one_degree) + shading::glare_flare(one_degree);
    return luminance(irradiance) * exposure * scene_->glare.strength * psf;
}

struct GlareSources::Candidate {
    GlareSource source;
    double rank;  // display value; the Suns rank first
};

namespace {

// A non-star source's weight: smoothstep from min_display to twice that, so nothing pops.
double fade_in(const GlareConfig& cfg, double display) {
    if (cfg.min_display <= 0.0) return 1.0;
    const double x = std::clamp((display - cfg.min_display) / cfg.min_display, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

// Irradiance at the camera (before the air) of body b at distance d in direction dir: a star's
// disc, or a Lambert sphere lit by the Sun (none without a Sun).
std::optional<glm::dvec3> body_irradiance(const BodyConfig& b, const BodyState& st, const glm::dvec3& dir, double d,
                                          const BodyState* sun_state, const BodyConfig* sun) {
    if (b.kind == BodyKind::Star) return glm::dvec3(b.tint) * atmosphere::sun_irradiance_scene_units(b, d);
    if (!sun_state) return std::nullopt;
    const glm::dvec3 to_sun = sun_state->position_m - st.position_m;
    const double e_sun = atmosphere::sun_irradiance_scene_units(*sun, glm::length(to_sun));
    const double phase = 2.0 * std::asin(std::clamp(0.5 * glm::length(glm::normalize(to_sun) - (-dir)), 0.0, 1.0));
    const double s = b.radius_m / d;
    return glm::dvec3(b.tint) * (2.0 / 3.0 * b.albedo * e_sun * s * s * lambert_phase(phase));
}

// Whether a body without air hides part of the Sun from the camera (a planet's own ground hiding
// the setting Sun does not count): in an eclipse the stars are not judged against the sky (the
// master's march, like the slaves' sky-view table, has no eclipse shadow in it).
bool sun_eclipsed(const Snapshot& snap, const SceneConfig& scene, const BodyState* sun_state, const BodyConfig* sun) {
    if (!sun_state || !sun) return false;
    const std::vector<SphereOccluder> airless = snapshot_occluders(snap, scene, sun_state->id, true);
    return analytic_visibility(snap.camera_position_m, sun_state->position_m, sun->radius_m, airless).visible_fraction <
           1.0;
}

}  // namespace

glm::dvec3 GlareSources::transmittance(const Snapshot& snap, const glm::dvec3& dir) const {
    return atmospheres_ ? atmospheres_->transmittance(snap, dir) : glm::dvec3(1.0);
}

std::vector<GlareSource> GlareSources::select(const Snapshot& snap) const {
    std::vector<GlareSource> out;
    const GlareConfig& cfg = scene_->glare;
    if (!cfg.enabled) return out;
    std::vector<Candidate> candidates;
    add_body_candidates(snap, candidates);
    add_catalog_candidates(snap, candidates);
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.rank > b.rank; });
    for (const auto& c : candidates) {
        if (static_cast<int>(out.size()) >= cfg.max_sources) break;
        out.push_back(c.source);
    }
    return out;
}

void GlareSources::add_body_candidates(const Snapshot& snap, std::vector<Candidate>& candidates) const {
    const glm::dvec3 cam = snap.camera_position_m;
    const BodyState* sun_state = find_star(snap, *scene_);
    const BodyConfig* sun = sun_state ? &scene_->bodies[sun_state->id] : nullptr;
    for (const auto& st : snap.bodies) {
        if (st.id >= scene_->bodies.size()) continue;
        const BodyConfig& b = scene_->bodies[st.id];
        const glm::dvec3 to = st.position_m - cam;
        const double d = glm::length(to);
        if (!(d > b.radius_m)) continue;  // inside it: no glare from it
        const glm::dvec3 dir = to / d;
        const std::optional<glm::dvec3> unattenuated = body_irradiance(b, st, dir, d, sun_state, sun);
        if (!unattenuated) continue;
        const glm::dvec3 e = *unattenuated * transmittance(snap, dir);
        double weight = 1.0;
        double rank = 1e300;
        if (b.kind != BodyKind::Star) {
            // A glare is the eye's response to a small bright source; a wide disc spreads its own.
            if (b.radius_m / d > std::sin(kMaxBodyRadius)) continue;
            rank = display_at_one_degree(e, snap.settings.exposure);
            weight = fade_in(scene_->glare, rank);
            if (weight <= 0.0) continue;
        }
        GlareSource g;
        g.body = b.id;
        g.direction = glm::vec3(dir);
        g.angular_radius = static_cast<float>(std::asin(std::min(b.radius_m / d, 1.0)));
        g.irradiance = glm::vec3(e * weight);
        const GlareVisibility v =
            analytic_visibility(cam, st.position_m, b.radius_m, snapshot_occluders(snap, *scene_, b.id));
        g.visible_fraction = static_cast<float>(std::clamp(v.visible_fraction, 0.0, 1.0));
        g.centroid_offset = glm::vec3(v.centroid_offset);
        g.origin = GlareOrigin::Analytic;
        candidates.push_back({g, rank});
    }
}

void GlareSources::add_catalog_candidates(const Snapshot& snap, std::vector<Candidate>& candidates) const {
    if (stars_.empty()) return;
    const GlareConfig& cfg = scene_->glare;
    const std::vector<SphereOccluder> occluders = snapshot_occluders(snap, *scene_, GlareSource::kCatalogStar);
    const BodyState* sun_state = find_star(snap, *scene_);
    const BodyConfig* sun = sun_state ? &scene_->bodies[sun_state->id] : nullptr;
    // A star the eye cannot see against the sky behind it has no glare either (as the slaves
    // draw the star itself).
    const bool judge_sky = atmospheres_ && !sun_eclipsed(snap, *scene_, sun_state, sun);
    for (size_t i = 0; i < stars_.size(); ++i) {
        const Star& s = stars_[i];
        const glm::dvec3 dir = s.direction();
        const glm::dvec3 color(shading::bv_to_linear_srgb(s.b_minus_v));
        glm::dvec3 e = color * (scene_->stars.zero_mag_flux * std::pow(10.0, -0.4 * s.v_mag));
        // Cheap reject before the atmosphere: even undimmed it would not count.
        if (display_at_one_degree(e, snap.settings.exposure) < cfg.min_display) continue;
        e *= transmittance(snap, dir);
        if (judge_sky) e *= atmospheres_->star_sky_weight(snap, dir, s.v_mag, sun_state, sun);
        const double rank = display_at_one_degree(e, snap.settings.exposure);
        const double weight = fade_in(cfg, rank);
        if (weight <= 0.0) continue;
        GlareSource g;
        g.body = GlareSource::kCatalogStar;
        g.star = static_cast<uint32_t>(i);
        g.direction = glm::vec3(dir);
        g.angular_radius = 0.0f;
        g.irradiance = glm::vec3(e * weight);
        g.visible_fraction = point_visible(snap.camera_position_m, dir, occluders) ? 1.0f : 0.0f;
        g.origin = GlareOrigin::Analytic;
        candidates.push_back({g, rank});
    }
}

}  // namespace cupola

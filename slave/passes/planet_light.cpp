#include "passes/planet_light.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "atmosphere/solar_scale.hpp"
#include "scene/planet_magnitude.hpp"
#include "shading/shared_shading.hpp"
#include "scene/sky_positions.hpp"

namespace cupola {

namespace {

// The shared shading's Rec. 709 luminance (shared/gamut_map.glsl), as the shaders take it.
double luminance(const glm::dvec3& rgb) { return shading::rec709_luminance(glm::vec3(rgb)); }

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The Sun - body - camera geometry of the magnitude fits.
PlanetGeometry planet_geometry(const BodyState& s, const PlanetLightInputs& in) {
    return cupola::planet_geometry(s.position_m, s.orientation, in.sun_position_m, in.camera_position_m);
}

// The surface's lunar-Lambert weight at a phase angle (0 for a Lambert surface).
double limb_weight_at(const BodyConfig& b, double phase_rad) {
    if (b.photometry != Photometry::LunarLambert) return 0.0;
    return shading::lunar_lambert_limb_weight(static_cast<float>(phase_rad));
}

// The drawn disc's light without the phase function: the surface model's disc integral for the
// map's mean albedo, times how the map's lit, visible part compares with its mean (1 for
// map_ratio false), times an oblate spheroid's projected area over pi a^2.
double model_disc_flux(const BodyConfig& b, const BodyState& s, const PlanetGeometry& g, const PlanetLightInputs& in,
                       bool map_ratio) {
    const double irradiance = in.sun_irradiance_1au / (g.sun_distance_au * g.sun_distance_au);
    const double ratio = std::min(b.radius_m / (g.observer_distance_au * kAstronomicalUnit_m), 1.0);
    const double lat = glm::radians(g.sub_observer_latitude_deg), c = 1.0 - b.flattening;
    const double area = std::sqrt(c * c * std::cos(lat) * std::cos(lat) + std::sin(lat) * std::sin(lat));
    const double phase = glm::radians(g.phase_deg), limb_weight = limb_weight_at(b, phase);
    const glm::dquat to_body = glm::conjugate(s.orientation);
    const double map = !map_ratio
                           ? 1.0
                           : lit_map_ratio(in.map_grid, luminance(in.map_mean_rgb),
                                           to_body * glm::normalize(in.sun_position_m - s.position_m),
                                           to_body * glm::normalize(in.camera_position_m - s.position_m), limb_weight);
    return b.albedo * luminance(in.map_mean_rgb) * map * irradiance * ratio * ratio *
           lunar_lambert_disc_integral(phase, limb_weight) * area;
}

// The irradiance a body's measured phase curve gives at its observer (g), if it has one, for the
// body's own size: the curve's magnitude, a flux relative to the Sun's at 1 AU.
std::optional<double> curve_irradiance(const BodyConfig& b, const PlanetGeometry& g, double sun_irradiance_1au,
                                       bool with_rings = false) {
    const std::optional<double> ratio = phase_curve_irradiance_ratio(b.ephemeris, b.radius_m, g, with_rings);
    if (!ratio) return std::nullopt;
    return *ratio * sun_irradiance_1au;
}

// The measured phase curve's light at the camera, if the body has one.
std::optional<double> curve_flux(const BodyConfig& b, const PlanetGeometry& g, const PlanetLightInputs& in) {
    return curve_irradiance(b, g, in.sun_irradiance_1au);
}

// Saturn drawn with its rings: as a point it carries the globe's and the rings' light together
// (saturn_with_rings_magnitude_v); the disc stays the globe's curve and the rings draw their own light.
bool point_carries_rings(const BodyConfig& b) { return magnitude_includes_rings(b.ephemeris, b.rings.present); }

// The measured curve over the drawn model's light: what scales the disc's radiance. Past the
// curve's data it goes on as a Lambert sphere, as the model does there (the lunar-Lambert L is 0
// from 104 degrees on), so the scale stays the one at the curve's last phase angle (the ratio of
// two vanishing numbers near 180 degrees would not).
double disc_scale_for(const BodyConfig& b, const BodyState& s, const PlanetGeometry& g, const PlanetLightInputs& in,
                      double model) {
    const PhaseCurve* curve = find_phase_curve(b.ephemeris);
    if (g.phase_deg <= curve->max_phase_deg) return model > 0.0 ? *curve_flux(b, g, in) / model : 0.0;
    PlanetGeometry last = g;
    last.phase_deg = curve->max_phase_deg;
    const double model_there = model_disc_flux(b, s, last, in, false), uniform = model_disc_flux(b, s, g, in, false);
    if (!(model_there > 0.0) || !(model > 0.0)) return 0.0;
    return *curve_flux(b, last, in) / model_there * (uniform / model);  // over the map's lit part here
}

// The light the body a moon circles sends onto it, as body.frag takes it: seen from the camera at
// the shine's own phase angle, with the phase function there (the measured curve over a uniform
// model's integral, distance-free).
void set_planetshine(PlanetLight& light, const BodyConfig& b, const BodyState& s, const PlanetGeometry& g,
                     const PlanetLightInputs& in) {
    if (!in.shine || in.shine->irradiance <= 0.0) return;
    const glm::dvec3 to_source = in.shine->position_m - s.position_m;
    PlanetGeometry at_shine = g;
    at_shine.phase_deg = glm::degrees(angle_between(to_source, in.camera_position_m - s.position_m));
    double phase_scale = 1.0;
    if (const auto curve = curve_flux(b, at_shine, in)) {
        const double model = model_disc_flux(b, s, at_shine, in, false);
        phase_scale = model > 0.0 ? *curve / model : 0.0;
    }
    light.shine_dir = glm::normalize(to_source);
    light.shine_limb_weight = limb_weight_at(b, glm::radians(at_shine.phase_deg));
    light.shine_lit = phase_scale * b.albedo / std::numbers::pi * in.shine->irradiance * in.shine->unit_color;
}

}  // namespace

LuminanceGrid luminance_grid(int width, int height, const std::vector<float>& rgb, const glm::dvec3& tint) {
    LuminanceGrid g;
    g.cells.assign(LuminanceGrid::kWidth * LuminanceGrid::kHeight, 0.0f);
    std::vector<int> counts(g.cells.size(), 0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
            const size_t cell = static_cast<size_t>(y * LuminanceGrid::kHeight / height) * LuminanceGrid::kWidth +
                                static_cast<size_t>(x * LuminanceGrid::kWidth / width);
            g.cells[cell] += static_cast<float>(luminance(tint * glm::dvec3(p[0], p[1], p[2])));
            ++counts[cell];
        }
    for (size_t i = 0; i < g.cells.size(); ++i) g.cells[i] /= static_cast<float>(std::max(counts[i], 1));
    return g;
}

double lunar_lambert_disc_integral(double phase_rad, double limb_weight) {
    return limb_weight * lommel_seeliger_phase(phase_rad) + 2.0 / 3.0 * (1.0 - limb_weight) * lambert_phase(phase_rad);
}

double lit_map_ratio(const LuminanceGrid* grid, double mean_luminance, const glm::dvec3& to_sun,
                     const glm::dvec3& to_camera, double limb_weight) {
    if (!grid || grid->cells.empty() || mean_luminance <= 0.0) return 1.0;
    double with_map = 0.0, uniform = 0.0;
    for (int y = 0; y < LuminanceGrid::kHeight; ++y) {
        const double lat = (0.5 - (y + 0.5) / LuminanceGrid::kHeight) * std::numbers::pi;
        for (int x = 0; x < LuminanceGrid::kWidth; ++x) {
            const double lon = ((x + 0.5) / LuminanceGrid::kWidth - 0.5) * 2.0 * std::numbers::pi;
            const glm::dvec3 n(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
            const double cos_e = std::max(glm::dot(n, to_camera), 0.0);
            const double w = shading::lunar_lambert(static_cast<float>(glm::dot(n, to_sun)), static_cast<float>(cos_e),
                                                    static_cast<float>(limb_weight)) *
                             cos_e * std::cos(lat);
            with_map += w * grid->cells[static_cast<size_t>(y * LuminanceGrid::kWidth + x)];
            uniform += w * mean_luminance;
        }
    }
    return uniform > 0.0 ? with_map / uniform : 1.0;
}

double point_to_disc_start_rad(double psf_sigma_rad, double coarsest_pixel_rad) {
    return std::max(2.0 * psf_sigma_rad, 4.0 * coarsest_pixel_rad);
}

double planetshine_irradiance(const BodyConfig& source, const BodyState& source_state, double map_mean_luminance,
                              const glm::dvec3& lit_position_m, const glm::dvec3& sun_position_m,
                              double sun_irradiance_1au) {
    const glm::dvec3 to_sun = sun_position_m - source_state.position_m;
    const glm::dvec3 to_lit = lit_position_m - source_state.position_m;
    PlanetGeometry g;
    g.sun_distance_au = glm::length(to_sun) / kAstronomicalUnit_m;
    g.observer_distance_au = glm::length(to_lit) / kAstronomicalUnit_m;
    g.phase_deg = glm::degrees(angle_between(to_sun, to_lit));
    if (sun_irradiance_1au <= 0.0 ||
        g.observer_distance_au * kAstronomicalUnit_m < kPlanetshineMinRadii * source.radius_m)
        return 0.0;
    if (const auto curve = curve_irradiance(source, g, sun_irradiance_1au)) return *curve;
    const double ratio = source.radius_m / (g.observer_distance_au * kAstronomicalUnit_m);
    return 2.0 / 3.0 * source.albedo * map_mean_luminance * sun_irradiance_1au /
           (g.sun_distance_au * g.sun_distance_au) * ratio * ratio * lambert_phase(glm::radians(g.phase_deg));
}

namespace {

// From disc to point with the body's angular radius rho: the disc's weight and the point's width.
void set_handover(PlanetLight& light, double rho, const PlanetLightInputs& in) {
    light.disc_weight = glm::smoothstep(in.handover_start_rad, 2.0 * in.handover_start_rad, rho);
    light.point_sigma_rad = std::sqrt(in.psf_sigma_rad * in.psf_sigma_rad + 0.25 * rho * rho);
    light.supersample = rho < 4.0 * in.handover_start_rad ? kSmallDiscSupersample : 1;
    light.small_disc = rho < 8.0 * in.handover_start_rad;
}

}  // namespace

PlanetLight star_light(const BodyConfig& b, const BodyState& s, const PlanetLightInputs& in) {
    PlanetLight light;
    const double d = glm::length(in.camera_position_m - s.position_m);
    const double tint = luminance(glm::dvec3(b.tint));
    if (d <= b.radius_m || tint <= 0.0) return light;
    light.unit_color = glm::dvec3(b.tint) / tint;
    light.flux = atmosphere::sun_irradiance_scene_units(b.radiance, b.radius_m, b.limb_darkening_u, d) * tint;
    set_handover(light, std::asin(b.radius_m / d), in);
    return light;
}

double star_visible_fraction(const SkyDisc& star, const std::vector<SkyDisc>& nearer, double limb_u) {
    if (star.radius_rad <= 0.0) return 1.0;
    double visible = 1.0;
    for (const SkyDisc& o : nearer) {
        const double separation_rad = angle_between(star.center_dir, o.center_dir);
        visible *= shading::eclipse_visible_exact(static_cast<float>(o.radius_rad / star.radius_rad),
                                                  static_cast<float>(separation_rad / star.radius_rad),
                                                  static_cast<float>(limb_u));
    }
    return visible;
}

PlanetLight planet_light(const BodyConfig& b, const BodyState& s, const PlanetLightInputs& in) {
    PlanetLight light;
    const double mean = luminance(in.map_mean_rgb);
    light.unit_color = mean > 0.0 ? in.map_mean_rgb / mean : glm::dvec3(1.0);
    if (in.sun_irradiance_1au <= 0.0 || glm::length(in.camera_position_m - s.position_m) <= b.radius_m) return light;
    const PlanetGeometry g = planet_geometry(s, in);
    const double model = model_disc_flux(b, s, g, in, true);
    light.flux = model;
    light.limb_weight = limb_weight_at(b, glm::radians(g.phase_deg));
    if (const auto curve = curve_flux(b, g, in)) {
        light.flux = point_carries_rings(b) ? *curve_irradiance(b, g, in.sun_irradiance_1au, true) : *curve;
        light.disc_scale = disc_scale_for(b, s, g, in, model);
    }
    set_planetshine(light, b, s, g, in);
    set_handover(light, std::asin(std::min(b.radius_m / (g.observer_distance_au * kAstronomicalUnit_m), 1.0)), in);
    return light;
}

PlanetLight handover_light(const BodyConfig& b, const BodyState& s, const PlanetLightInputs& in) {
    PlanetLight light;
    const double d = glm::length(in.camera_position_m - s.position_m);
    if (in.sun_irradiance_1au <= 0.0 || d <= b.radius_m) return light;  // as planet_light
    set_handover(light, std::asin(b.radius_m / d), in);
    return light;
}

PlanetLight with_air(const PlanetLight& light, const glm::dvec3& air_flux_rgb) {
    PlanetLight out;
    out.supersample = light.supersample;  // the air's draw takes more rays a pixel
    if (light.disc_weight >= 1.0) return out;
    out = light;
    out.flux = luminance(air_flux_rgb);
    if (out.flux > 0.0) out.unit_color = air_flux_rgb / out.flux;
    out.disc_scale = 0.0;
    out.shine_lit = glm::dvec3(0.0);
    return out;
}

}  // namespace cupola

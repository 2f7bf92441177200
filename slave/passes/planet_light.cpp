#include "passes/planet_light.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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
    const glm::dvec3 to_sun = in.sun_position_m - s.position_m, to_camera = in.camera_position_m - s.position_m;
    const glm::dvec3 pole = s.orientation * glm::dvec3(0.0, 0.0, 1.0);
    PlanetGeometry g;
    g.sun_distance_au = glm::length(to_sun) / kAstronomicalUnit_m;
    g.observer_distance_au = glm::length(to_camera) / kAstronomicalUnit_m;
    g.phase_deg = glm::degrees(angle_between(to_sun, to_camera));
    g.sub_sun_latitude_deg = glm::degrees(std::asin(std::clamp(glm::dot(pole, glm::normalize(to_sun)), -1.0, 1.0)));
    g.sub_observer_latitude_deg =
        glm::degrees(std::asin(std::clamp(glm::dot(pole, glm::normalize(to_camera)), -1.0, 1.0)));
    return g;
}

// The drawn disc's light: a Lambert sphere (oblate: times its projected area over pi a^2).
double lambert_disc_flux(const BodyConfig& b, const BodyState& s, const PlanetGeometry& g,
                         const PlanetLightInputs& in) {
    const double irradiance = in.sun_irradiance_1au / (g.sun_distance_au * g.sun_distance_au);
    const double ratio = std::min(b.radius_m / (g.observer_distance_au * kAstronomicalUnit_m), 1.0);
    const double lat = glm::radians(g.sub_observer_latitude_deg), c = 1.0 - b.flattening;
    const double area = std::sqrt(c * c * std::cos(lat) * std::cos(lat) + std::sin(lat) * std::sin(lat));
    const glm::dquat to_body = glm::conjugate(s.orientation);
    const double map = lit_map_ratio(in.map_grid, luminance(in.map_mean_rgb),
                                     to_body * glm::normalize(in.sun_position_m - s.position_m),
                                     to_body * glm::normalize(in.camera_position_m - s.position_m));
    return 2.0 / 3.0 * b.albedo * luminance(in.map_mean_rgb) * map * irradiance * ratio * ratio *
           lambert_phase(glm::radians(g.phase_deg)) * area;
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

double lit_map_ratio(const LuminanceGrid* grid, double mean_luminance, const glm::dvec3& to_sun,
                     const glm::dvec3& to_camera) {
    if (!grid || grid->cells.empty() || mean_luminance <= 0.0) return 1.0;
    double with_map = 0.0, uniform = 0.0;
    for (int y = 0; y < LuminanceGrid::kHeight; ++y) {
        const double lat = (0.5 - (y + 0.5) / LuminanceGrid::kHeight) * std::numbers::pi;
        for (int x = 0; x < LuminanceGrid::kWidth; ++x) {
            const double lon = ((x + 0.5) / LuminanceGrid::kWidth - 0.5) * 2.0 * std::numbers::pi;
            const glm::dvec3 n(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
            const double w = std::max(glm::dot(n, to_sun), 0.0) * std::max(glm::dot(n, to_camera), 0.0) * std::cos(lat);
            with_map += w * grid->cells[static_cast<size_t>(y * LuminanceGrid::kWidth + x)];
            uniform += w * mean_luminance;
        }
    }
    return uniform > 0.0 ? with_map / uniform : 1.0;
}

double point_to_disc_start_rad(double psf_sigma_rad, double coarsest_pixel_rad) {
    return std::max(2.0 * psf_sigma_rad, 4.0 * coarsest_pixel_rad);
}

PlanetLight planet_light(const BodyConfig& b, const BodyState& s, const PlanetLightInputs& in) {
    PlanetLight light;
    const double mean = luminance(in.map_mean_rgb);
    light.unit_color = mean > 0.0 ? in.map_mean_rgb / mean : glm::dvec3(1.0);
    if (in.sun_irradiance_1au <= 0.0 || glm::length(in.camera_position_m - s.position_m) <= b.radius_m) return light;
    const PlanetGeometry g = planet_geometry(s, in);
    const double lambert = lambert_disc_flux(b, s, g, in);
    light.flux = lambert;
    if (const auto v = planet_magnitude_v(b.ephemeris, g)) {
        light.flux = in.sun_irradiance_1au * std::pow(10.0, -0.4 * (*v - kSunMagnitudeV));
        light.disc_scale = lambert > 0.0 ? light.flux / lambert : 0.0;
    }
    const double rho = std::asin(std::min(b.radius_m / (g.observer_distance_au * kAstronomicalUnit_m), 1.0));
    light.disc_weight = glm::smoothstep(in.handover_start_rad, 2.0 * in.handover_start_rad, rho);
    light.small_disc = rho < 8.0 * in.handover_start_rad;
    light.point_sigma_rad = std::sqrt(in.psf_sigma_rad * in.psf_sigma_rad + 0.25 * rho * rho);
    return light;
}

}  // namespace cupola

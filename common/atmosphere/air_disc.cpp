#include "atmosphere/air_disc.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shading/shared_shading.hpp"

namespace cupola::atmosphere {

namespace {

constexpr int kGroundRings = 24;           // impact parameters over the ground's disc
constexpr int kAirRings = 8;               // over the shell of air beyond its limb, where the rim is bright
constexpr int kHalfTurns = 24;             // position angles over half the disc (it is symmetric about the Sun's plane)
constexpr double kReferenceRadii = 100.0;  // the observer's distance, in top-of-atmosphere radii

struct DiscParts {
    glm::dvec3 air{0.0}, ground{0.0};  // linear sRGB radiance x area on the plane through the centre (m^2)
};

// Per unit solar irradiance at the sample wavelengths -> linear sRGB (Y in cd m^-2), unclipped.
glm::dvec3 to_rgb(const ProductionAtmosphere& m, const glm::vec3& f) {
    return glm::dvec3(shading::xyz_to_linear_srgb(glm::vec3(m.to_xyz(f))));
}

// One ring of impact parameters [b0, b1] (metres from the centre, on the plane through the centre
// facing the observer at distance d): its light, by the midpoint rule in b and in position angle.
DiscParts ring_light(const ProductionAtmosphere& m, double b0, double b1, double d, const glm::vec3& sun) {
    DiscParts out;
    const double b = 0.5 * (b0 + b1), dtheta = std::numbers::pi / kHalfTurns;
    const glm::dvec3 camera(0.0, 0.0, d);
    for (int k = 0; k < kHalfTurns; ++k) {
        const double theta = (k + 0.5) * dtheta;
        const glm::dvec3 v = glm::normalize(glm::dvec3(b * std::cos(theta), b * std::sin(theta), 0.0) - camera);
        const shading::AtmosphereRayStart st = shading::atm_ray_start(m.shader_params(), static_cast<float>(d),
                                                                      glm::vec3(v), glm::vec3(0.0f, 0.0f, -1.0f), sun);
        if (!st.valid) continue;
        const ProductionAtmosphere::RadianceParts p = m.radiance_parts(st);
        const double area = 2.0 * b * (b1 - b0) * dtheta;  // both halves
        out.air += to_rgb(m, p.air) * area;
        out.ground += to_rgb(m, p.ground_per_albedo) * area;
    }
    return out;
}

DiscParts disc_light(const ProductionAtmosphere& m, double phase_rad) {
    const shading::AtmosphereParams& a = m.shader_params();
    const double ground_m = a.bottom_radius_m, top_m = a.top_radius_m, d = kReferenceRadii * top_m;
    const glm::vec3 sun(static_cast<float>(std::sin(phase_rad)), 0.0f, static_cast<float>(std::cos(phase_rad)));
    DiscParts sum;
    const auto add_rings = [&](double from_m, double to_m, int rings) {
        for (int i = 0; i < rings; ++i) {
            const DiscParts r =
                ring_light(m, from_m + (to_m - from_m) * i / rings, from_m + (to_m - from_m) * (i + 1) / rings, d, sun);
            sum.air += r.air;
            sum.ground += r.ground;
        }
    };
    add_rings(0.0, ground_m, kGroundRings);
    add_rings(ground_m, top_m, kAirRings);
    return sum;
}

}  // namespace

AirDiscCurve::AirDiscCurve(const ProductionAtmosphere& model) {
    const int steps = static_cast<int>(std::lround(180.0 / kPhaseStepDeg)) + 1;
    for (int i = 0; i < steps; ++i) {
        const DiscParts p = disc_light(model, i * kPhaseStepDeg * std::numbers::pi / 180.0);
        air_.push_back(p.air);
        ground_.push_back(p.ground);
    }
}

glm::dvec3 AirDiscCurve::flux_rgb(double phase_deg, const glm::dvec3& ground_rgb, double distance_m) const {
    const double x = std::clamp(phase_deg, 0.0, 180.0) / kPhaseStepDeg;
    const int i = std::min(static_cast<int>(x), static_cast<int>(air_.size()) - 2);
    const double f = x - i;
    const glm::dvec3 air = glm::mix(air_[i], air_[i + 1], f), ground = glm::mix(ground_[i], ground_[i + 1], f);
    return (air + ground_rgb * ground) / (distance_m * distance_m);
}

}  // namespace cupola::atmosphere

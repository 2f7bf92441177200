// A planet with air as a distant observer sees it whole (atmosphere/air_disc): the ground seen
// through the air is a Lambert sphere dimmed by the air's transmittance in and out, the more at
// larger phase angles (longer slant paths); the air adds a blue light of its own, several per
// cent of a white sphere's; the light falls as the square of the distance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "atmosphere/air_disc.hpp"
#include "atmosphere/production_model.hpp"
#include "atmosphere/solar_scale.hpp"
#include "shading/shared_shading.hpp"

namespace at = cupola::atmosphere;

namespace {

double luminance(const glm::dvec3& rgb) { return cupola::shading::rec709_luminance(glm::vec3(rgb)); }

// A Lambert sphere of albedo 1 and radius r_m in an illuminance e: its light times the distance
// squared, (2/3) e r^2 Phi(alpha), Phi(alpha) = (sin alpha + (pi - alpha) cos alpha) / pi.
double lambert_sphere(double e, double r_m, double alpha_rad) {
    const double phi = (std::sin(alpha_rad) + (std::numbers::pi - alpha_rad) * std::cos(alpha_rad)) / std::numbers::pi;
    return 2.0 / 3.0 * e * r_m * r_m * phi;
}

}  // namespace

TEST(AirDisc, TheGroundThroughTheAirIsALambertSphereDimmedAndTheAirAddsBlue) {
    at::TableCacheOptions no_cache;
    no_cache.enabled = false;
    const at::ProductionAtmosphere m(at::AtmosphereParameters::earth(), at::production_quality("sky-view"), no_cache);
    const at::AirDiscCurve curve(m);
    const double e = at::physical_solar_illuminance(m), r = m.shader_params().bottom_radius_m;
    double previous_dimming = 1.0;
    for (int step = 0; step <= 18; step += 3) {  // 0 to 90 degrees
        const double alpha = step * at::AirDiscCurve::kPhaseStepDeg * std::numbers::pi / 180.0;
        const double dimming = luminance(curve.ground_at(step)) / lambert_sphere(e, r, alpha);
        const glm::dvec3 air = curve.air_at(step);
        std::printf("phase %4.0f: ground %.3f of a Lambert sphere; air %.4f of a white one, blue/red %.2f\n",
                    glm::degrees(alpha), dimming, luminance(air) / lambert_sphere(e, r, alpha), air.b / air.r);
        // The air's vertical transmittance at 550 nm is about 0.9: in and out, 0.8 at best.
        EXPECT_GT(dimming, 0.5) << glm::degrees(alpha);
        EXPECT_LT(dimming, 0.9) << glm::degrees(alpha);
        EXPECT_LT(dimming, previous_dimming + 1e-3) << glm::degrees(alpha);
        previous_dimming = dimming;
        EXPECT_GT(air.b, 2.0 * air.r) << glm::degrees(alpha);           // Rayleigh blue
        EXPECT_GT(luminance(air), 0.03 * lambert_sphere(e, r, alpha));  // Rayleigh depth 0.1 at 550 nm
        EXPECT_LT(luminance(air), 0.3 * lambert_sphere(e, r, alpha));
    }
    // The light falls as the distance squared, and interpolates between steps.
    const glm::dvec3 white(1.0);
    const glm::dvec3 near = curve.flux_rgb(30.0, white, 1e9), far = curve.flux_rgb(30.0, white, 2e9);
    EXPECT_NEAR(luminance(near) / luminance(far), 4.0, 1e-6);
    const double between = luminance(curve.flux_rgb(32.5, white, 1e9));
    const double a = luminance(curve.flux_rgb(30.0, white, 1e9)), b = luminance(curve.flux_rgb(35.0, white, 1e9));
    EXPECT_NEAR(between, 0.5 * (a + b), 1e-6 * a);  // luminance in float
}

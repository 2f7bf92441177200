// CPU tests of the shading functions in shaders/shared/*.glsl, compiled as C++ through
// common/shading/shared_shading.hpp (the GPU runs the same text; test_egl_render compares them).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "shading/shared_shading.hpp"

namespace sh = cupola::shading;

TEST(SharedShading, LimbDarkeningEdgeValues) {
    EXPECT_FLOAT_EQ(sh::limb_darkening(1.0f, 0.6f), 1.0f);  // disc centre
    EXPECT_FLOAT_EQ(sh::limb_darkening(0.0f, 0.6f), 0.4f);  // limb: 1 - u
    EXPECT_FLOAT_EQ(sh::limb_darkening(0.5f, 0.6f), 0.7f);
    EXPECT_FLOAT_EQ(sh::limb_darkening(0.3f, 0.0f), 1.0f);   // no darkening
    EXPECT_FLOAT_EQ(sh::limb_darkening(-0.2f, 0.6f), 0.4f);  // clamped outside the disc
}

TEST(SharedShading, LimbDarkeningDiscAverageMatchesIntegral) {
    // Mean over the projected disc: the area element in mu is 2 mu dmu.
    for (float u : {0.0f, 0.3f, 0.6f, 1.0f}) {
        double sum = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            const double mu = (i + 0.5) / n;
            sum += sh::limb_darkening(static_cast<float>(mu), u) * 2.0 * mu / n;
        }
        EXPECT_NEAR(sum, sh::limb_darkening_disc_average(u), 1e-5) << "u=" << u;
    }
}

TEST(SharedShading, StarPsfIntegratesToOneOverTheSphere) {
    for (double sigma_arcmin : {0.5, 2.0, 10.0, 60.0}) {
        const double sigma = sigma_arcmin / 60.0 * std::numbers::pi / 180.0;
        // integral of psf(a) 2 pi sin(a) da, out to 12 sigma (the rest is < 1e-30).
        const double amax = std::min(12.0 * sigma, std::numbers::pi);
        const int n = 200000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const double a = (i + 0.5) * amax / n;
            sum += sh::star_psf(static_cast<float>(a), static_cast<float>(sigma)) * 2.0 * std::numbers::pi *
                   std::sin(a) * (amax / n);
        }
        EXPECT_NEAR(sum, 1.0, 1e-3) << "sigma " << sigma_arcmin << " arcmin";
    }
}

TEST(SharedShading, StarPsfPeaksAtZeroAndFalls) {
    const float sigma = 5.8e-4f;
    EXPECT_GT(sh::star_psf(0.0f, sigma), sh::star_psf(0.5f * sigma, sigma));
    EXPECT_NEAR(sh::star_psf(sigma, sigma) / sh::star_psf(0.0f, sigma), std::exp(-0.5), 1e-5);
    EXPECT_LT(sh::star_psf(5.0f * sigma, sigma) / sh::star_psf(0.0f, sigma), 1e-5);
}

TEST(SharedShading, AngleBetweenUnitsIsAccurateForTinyAngles) {
    const double a = 1e-4;  // 0.34 arcmin: acos(dot) in float would give 0 or ~3.5e-4
    const sh::vec3 x(1.0f, 0.0f, 0.0f);
    const sh::vec3 y(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
    EXPECT_NEAR(sh::angle_between_units(x, y), a, 1e-3 * a);
    EXPECT_NEAR(sh::angle_between_units(x, sh::vec3(0.0f, 1.0f, 0.0f)), std::numbers::pi / 2, 1e-6);
    EXPECT_NEAR(sh::angle_between_units(x, -x), std::numbers::pi, 1e-6);
}

TEST(SharedShading, BvTemperatureFollowsBallesteros) {
    // Ballesteros (2012): B-V 0 -> ~10 120 K; the Sun (B-V 0.65) -> ~5 780 K; 1.5 -> ~3 790 K.
    EXPECT_NEAR(sh::bv_to_temperature(0.0f), 4600.0 * (1 / 1.7 + 1 / 0.62), 1.0);
    EXPECT_NEAR(sh::bv_to_temperature(0.65f), 5778.0, 10.0);
    EXPECT_NEAR(sh::bv_to_temperature(1.5f), 3793.0, 10.0);
    for (float bv = -0.4f; bv < 2.0f; bv += 0.1f)
        EXPECT_GT(sh::bv_to_temperature(bv), sh::bv_to_temperature(bv + 0.1f)) << bv;
}

TEST(SharedShading, BvColourHasUnitLuminanceAndGoesBlueToRed) {
    float last_ratio = 0.0f;
    for (float bv = -0.4f; bv <= 2.0f; bv += 0.1f) {
        const sh::vec3 c = sh::bv_to_linear_srgb(bv);
        EXPECT_GE(c.x, 0.0f);
        EXPECT_GE(c.y, 0.0f);
        EXPECT_GE(c.z, 0.0f);
        EXPECT_NEAR(0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z, 1.0f, 1e-5f) << bv;
        const float ratio = c.x / std::max(c.z, 1e-6f);  // red / blue grows with B-V
        EXPECT_GT(ratio, last_ratio) << "B-V " << bv;
        last_ratio = ratio;
    }
    const sh::vec3 hot = sh::bv_to_linear_srgb(-0.3f), cool = sh::bv_to_linear_srgb(1.6f);
    EXPECT_GT(hot.z, hot.x);    // B stars are blue-white
    EXPECT_GT(cool.x, cool.z);  // M stars are orange-red
    // The Sun (B-V 0.65, ~5800 K) is close to white in sRGB (D65 ~ 6500 K): within 25 % per channel.
    const sh::vec3 sun = sh::bv_to_linear_srgb(0.65f);
    EXPECT_NEAR(sun.x, 1.0f, 0.25f);
    EXPECT_NEAR(sun.y, 1.0f, 0.25f);
    EXPECT_NEAR(sun.z, 1.0f, 0.35f);
}

TEST(SharedShading, ErfApproximationIsAccurate) {
    for (double x = -4.0; x <= 4.0; x += 0.01)
        EXPECT_NEAR(sh::erf_approx(static_cast<float>(x)), std::erf(x), 3e-7) << x;
}

TEST(SharedShading, StarBoxFractionsSumToOneAndMatchTheIntegral) {
    // A star sampled by pixels much larger, comparable to and smaller than its sigma: the
    // box fractions over a tiling sum to 1 (energy kept at any resolution), and the centroid of
    // the fractions is the star's position to 2% of sigma when pixels resolve the PSF, and to the
    // sampling limit (half a pixel) when the whole star falls in one or two pixels.
    const float sigma = 1e-3f;
    const sh::vec2 t(0.3f, -0.2f);
    const sh::vec2 st = sh::star_tangent_sigma(t, sigma);
    for (float pixel : {0.2f * sigma, sigma, 7.0f * sigma, 40.0f * sigma}) {
        double sum = 0, cx = 0, cy = 0;
        const int n = static_cast<int>(std::ceil(12.0 * sigma / pixel)) + 2;
        // A grid whose pixel phase relative to the star is arbitrary (0.37 px).
        const float x0 = t.x - (n + 0.37f) * pixel, y0 = t.y - (n + 0.61f) * pixel;
        for (int j = 0; j < 2 * n + 2; ++j)
            for (int i = 0; i < 2 * n + 2; ++i) {
                sh::vec2 lo(x0 + i * pixel, y0 + j * pixel), hi(lo.x + pixel, lo.y + pixel);
                double f = sh::star_box_fraction(t, st, lo, hi);
                sum += f;
                cx += f * (lo.x + 0.5 * pixel);
                cy += f * (lo.y + 0.5 * pixel);
            }
        EXPECT_NEAR(sum, 1.0, 1e-4) << "pixel/sigma " << pixel / sigma;
        const double tol = pixel <= sigma ? 0.02 * sigma : 0.5 * pixel;
        EXPECT_NEAR(cx / sum, t.x, tol) << "pixel/sigma " << pixel / sigma;
        EXPECT_NEAR(cy / sum, t.y, tol) << "pixel/sigma " << pixel / sigma;
    }
    // On the axis the tangent sigma is the angular sigma; off axis the radial one is smaller in
    // angle per tangent unit, so the tangent sigma grows (cos^2 radially, cos tangentially).
    const sh::vec2 on = sh::star_tangent_sigma(sh::vec2(0.0f, 0.0f), sigma);
    EXPECT_NEAR(on.x, sigma, 1e-9);
    const sh::vec2 off = sh::star_tangent_sigma(sh::vec2(1.0f, 0.0f), sigma);  // 45 degrees off axis
    EXPECT_NEAR(off.x, sigma * 2.0f, 1e-6);                                    // 1 / cos^2(45)
    EXPECT_NEAR(off.y, sigma * std::sqrt(2.0f), 1e-6);                         // 1 / cos(45)
}

TEST(SharedShading, TerrainLightOnSlopesAndTheGeomorphFactor) {
    using glm::vec3;
    const vec3 up(0, 0, 1), t(0.5f, 0.6f, 0.7f), sky(0.1f, 0.2f, 0.3f);
    const float el = 5.0f * std::numbers::pi_v<float> / 180.0f;  // the Sun 5 degrees up, to +x
    const vec3 sun(std::cos(el), 0.0f, std::sin(el));
    // A horizontal plane: the direct light by the Sun's zenith cosine, the whole sky.
    const vec3 flat = sh::terrain_illuminance(t, sky, up, up, sun);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(flat[c], t[c] * std::sin(el) + sky[c], 1e-6f);
    // A 30-degree slope facing the low Sun gets several times the direct light; facing away, none,
    // and the sky it sees is (1 + cos 30) / 2 of the whole.
    const float tilt = 30.0f * std::numbers::pi_v<float> / 180.0f;
    const vec3 toward(std::sin(tilt), 0.0f, std::cos(tilt)), away(-std::sin(tilt), 0.0f, std::cos(tilt));
    const vec3 lit = sh::terrain_illuminance(t, vec3(0.0f), toward, up, sun);
    EXPECT_GT(lit.x, 5.0f * t.x * std::sin(el));
    const vec3 dark = sh::terrain_illuminance(t, sky, away, up, sun);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(dark[c], sky[c] * 0.5f * (1.0f + std::cos(tilt)), 1e-6f);
    // A wall sees half the sky.
    EXPECT_NEAR(sh::terrain_illuminance(vec3(0.0f), sky, vec3(0, 1, 0), up, sun).z, 0.5f * sky.z, 1e-6f);
    // The geomorph: its own shape to 0.7 of the far distance, the parent's from it, monotone between.
    EXPECT_EQ(sh::terrain_morph(0.0f, 1000.0f), 1.0f);
    EXPECT_EQ(sh::terrain_morph(700.0f, 1000.0f), 1.0f);
    EXPECT_EQ(sh::terrain_morph(1000.0f, 1000.0f), 0.0f);
    EXPECT_EQ(sh::terrain_morph(5000.0f, 1000.0f), 0.0f);
    EXPECT_EQ(sh::terrain_morph(5000.0f, 0.0f), 1.0f);  // no morph distance: its own shape
    float last = 1.0f;
    for (float d = 700.0f; d <= 1000.0f; d += 10.0f) {
        const float m = sh::terrain_morph(d, 1000.0f);
        EXPECT_LE(m, last);
        last = m;
    }
}

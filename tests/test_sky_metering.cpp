// The exposure's metering statistics (common/exposure/sky_metering): the solid-angle-weighted
// log-average over what is lit, the highlight quantile, and the solid angle of an image-plane
// cell. A black sky around a lit planet does not change what is metered, only its lit share.
#include <gtest/gtest.h>

#include <cmath>

#include "exposure/sky_metering.hpp"

using namespace cupola;

TEST(SkyMetering, LogAverageWeightedBySolidAngle) {
    EXPECT_NEAR(meter_sky({{1.0, 1.0}, {100.0, 1.0}}).log_average, 10.0, 1e-9);
    // Three times the solid angle at 1 cd/m2: exp((3 ln 1 + ln 100) / 4) = 100^(1/4).
    EXPECT_NEAR(meter_sky({{1.0, 3.0}, {100.0, 1.0}}).log_average, std::pow(100.0, 0.25), 1e-9);
    // The arithmetic mean would be 50.5; a few bright samples do not dominate the log-average.
    EXPECT_LT(meter_sky({{1.0, 1.0}, {100.0, 1.0}}).log_average, 50.0);
}

TEST(SkyMetering, ABlackSkyAroundALitPlanetIsNotMetered) {
    const std::vector<MeterSample> planet = {{5000.0, 1.0}, {2000.0, 1.0}, {8000.0, 0.5}};
    const SkyMetering alone = meter_sky(planet);
    std::vector<MeterSample> in_space = planet;
    in_space.push_back({0.0, 10.0});                                      // black
    in_space.push_back({8000.0 * SkyMetering::kLitContrast * 0.5, 2.0});  // a faint haze below what is lit
    const SkyMetering seen = meter_sky(in_space);
    EXPECT_DOUBLE_EQ(seen.log_average, alone.log_average);
    EXPECT_DOUBLE_EQ(seen.highlight, alone.highlight);
    EXPECT_DOUBLE_EQ(alone.lit_fraction, 1.0);
    EXPECT_NEAR(seen.lit_fraction, 2.5 / 14.5, 1e-12);
    // Nothing lit: nothing metered.
    const SkyMetering night = meter_sky({{0.0, 1.0}, {std::nan(""), 1.0}, {-1.0, 1.0}});
    EXPECT_EQ(night.log_average, 0.0);
    EXPECT_EQ(night.highlight, 0.0);
}

TEST(SkyMetering, TheHighlightIsTheWeightedQuantile) {
    // 98.5 % of the solid angle at 1, 1.5 % at 1000: the 99th percentile is 1000.
    EXPECT_DOUBLE_EQ(meter_sky({{1.0, 98.5}, {1000.0, 1.5}}).highlight, 1000.0);
    // 99.5 % at 1, 0.5 % at 1000: 1 (at most 1 % of the view may clip).
    EXPECT_DOUBLE_EQ(meter_sky({{1.0, 99.5}, {1000.0, 0.5}}).highlight, 1.0);
    // Weights, not counts: one heavy sample outweighs many light ones.
    std::vector<MeterSample> s(100, {2.0, 0.001});
    s.push_back({30.0, 10.0});
    EXPECT_DOUBLE_EQ(meter_sky(s).highlight, 30.0);
}

// The cells of a frustum's image plane sum to its solid angle: a rectangular pyramid of half
// angles a and b subtends 4 asin(sin a sin b).
TEST(SkyMetering, ImagePlaneCellsSumToTheFrustumSolidAngle) {
    for (const auto& [a_deg, b_deg] : {std::pair{45.0, 45.0}, {50.0, 40.0}, {10.0, 70.0}}) {
        const double a = a_deg * M_PI / 180.0, b = b_deg * M_PI / 180.0;
        const int n = 400;
        const double dx = 2.0 * std::tan(a) / n, dy = 2.0 * std::tan(b) / n;
        double sum = 0.0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                sum +=
                    image_plane_cell_solid_angle(-std::tan(a) + (i + 0.5) * dx, -std::tan(b) + (j + 0.5) * dy, dx, dy);
        EXPECT_NEAR(sum, 4.0 * std::asin(std::sin(a) * std::sin(b)), 1e-4) << a_deg << " x " << b_deg;
    }
}

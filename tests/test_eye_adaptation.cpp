// The eye's adaptation and the exposure decided from it (common/exposure/eye_adaptation): the
// key of Krawczyk et al. (2005) falling at night, the exponential approach in log luminance with
// a fast time constant toward light and a slow one toward dark, and the display white.
#include <gtest/gtest.h>

#include <cmath>

#include "exposure/eye_adaptation.hpp"

using namespace cupola;

namespace {
AutoExposureConfig config() {
    AutoExposureConfig c;
    c.enabled = true;
    c.key = 0.18;
    c.light_adaptation_s = 1.0;
    c.dark_adaptation_s = 120.0;
    c.min_exposure = 1e-9;
    c.max_exposure = 1e6;
    return c;
}
}  // namespace

TEST(EyeAdaptation, TheKeyFallsAtNightAfterKrawczyk) {
    // 1.03 - 2 / (2 + log10(L + 1)) at published anchors of the formula.
    EXPECT_NEAR(adaptation_key(0.0), 0.03, 1e-12);
    EXPECT_NEAR(adaptation_key(9.0), 1.03 - 2.0 / 3.0, 1e-12);
    EXPECT_NEAR(adaptation_key(99.0), 0.53, 1e-12);
    double last = 0.0;
    for (double l = 1e-6; l < 1e6; l *= 3.0) {
        EXPECT_GT(adaptation_key(l), last);
        last = adaptation_key(l);
    }
    // Daylight: the configured key. Night (1e-3 cd/m2): 0.03, so the sky is shown dark.
    const AutoExposureConfig c = config();
    SkyMetering day;
    day.log_average = day.highlight = 5000.0;
    EXPECT_NEAR(decide_exposure(day, 5000.0, c).exposure, 0.18 / 5000.0, 1e-15);
    EXPECT_NEAR(decide_exposure(day, 1e-3, c).exposure, adaptation_key(1e-3) / 1e-3, 1e-9);
    AutoExposureConfig fixed_key = c;
    fixed_key.key_follows_adaptation = false;
    EXPECT_NEAR(decide_exposure(day, 1e-3, fixed_key).exposure, 0.18 / 1e-3, 1e-9);
}

TEST(EyeAdaptation, LightInASecondDarkInMinutesInLogLuminance) {
    const AutoExposureConfig c = config();
    // After one time constant, e^-1 of the log distance is left.
    const double up = adapt_luminance(1.0, 1000.0, 1.0, c);
    EXPECT_NEAR(std::log(1000.0 / up), std::log(1000.0) * std::exp(-1.0), 1e-9);
    const double down = adapt_luminance(1000.0, 1.0, 120.0, c);
    EXPECT_NEAR(std::log(down), std::log(1000.0) * std::exp(-1.0), 1e-9);
    // A second toward the dark does little, toward the light most of the way.
    EXPECT_GT(adapt_luminance(1000.0, 1.0, 1.0, c), 900.0);
    EXPECT_GT(adapt_luminance(1.0, 1000.0, 3.0, c), 500.0);
    // No time, no change; a zero time constant adapts at once.
    EXPECT_DOUBLE_EQ(adapt_luminance(5.0, 50.0, 0.0, c), 5.0);
    AutoExposureConfig instant = c;
    instant.dark_adaptation_s = 0.0;
    EXPECT_DOUBLE_EQ(adapt_luminance(50.0, 5.0, 0.01, instant), 5.0);
}

TEST(EyeAdaptation, TheFirstFrameStartsAdaptedThenFollows) {
    const AutoExposureConfig c = config();
    EyeAdaptation eye;
    EXPECT_FALSE(eye.adapted());
    EXPECT_DOUBLE_EQ(eye.step(300.0, 0.25, c), 300.0);
    double l = 300.0;
    for (int f = 0; f < 40; ++f) l = eye.step(0.01, 0.25, c);  // 10 s into the dark: still bright
    EXPECT_GT(l, 300.0 * std::pow(0.01 / 300.0, 1.0 - std::exp(-10.0 / 120.0)) * 0.999);
    EXPECT_LT(l, 300.0);
    EXPECT_DOUBLE_EQ(*eye.adapted(), l);
}

TEST(EyeAdaptation, TheDisplayWhiteIsTheExposedHighlightAtLeastOne) {
    const AutoExposureConfig c = config();
    SkyMetering m;
    m.log_average = 100.0;
    m.highlight = 4000.0;
    const ExposureDecision d = decide_exposure(m, 100.0, c);
    EXPECT_NEAR(d.tone_white, d.exposure * 4000.0, 1e-9);
    m.highlight = 101.0;  // low contrast: white 1, where the curve is the identity up to 1
    EXPECT_DOUBLE_EQ(decide_exposure(m, 100.0, c).tone_white, 1.0);
    EXPECT_DOUBLE_EQ(decide_exposure(SkyMetering{}, kDarkestAdaptation_cd_m2, c).tone_white, 0.0);
    EXPECT_DOUBLE_EQ(adaptation_target(SkyMetering{}), kDarkestAdaptation_cd_m2);
}

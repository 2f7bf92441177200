// The stars' twinkling (shaders/shared/star_twinkle.glsl on the CPU, and StarPass::twinkle_for):
// the airmass of Kasten and Young (1989) at its published values, the amplitude of Young (1967)
// rising as the airmass to the power 1.5 and falling with the observer's height, a factor of mean
// 1 and the model's deviation, the same for the same star and clock, and the modes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "passes/star_pass.hpp"
#include "shading/shared_shading.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {

// Mean and relative deviation of a star's factor over a minute at 60 frames a second.
std::pair<double, double> factor_statistics(unsigned star, float sigma) {
    double sum = 0.0, sum2 = 0.0;
    const int n = 3600;
    for (int i = 0; i < n; ++i) {
        const double f = sh::twinkle_factor(star, static_cast<float>(i) / 60.0f, sigma);
        sum += f;
        sum2 += f * f;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(sum2 / n - mean * mean, 0.0)) / mean};
}

}  // namespace

TEST(StarTwinkle, AirmassIsKastenAndYoungs) {
    // Kasten and Young's (1989) table from the integration through their model atmosphere: 1.000
    // at the zenith, 1.995 at 60 deg, 5.600 at 80 deg, 10.32 at 85 deg, 38.09 at the horizon.
    // Their approximation formula, which the shader evaluates, keeps within 0.5 % of it.
    const double deg = M_PI / 180.0;
    auto at = [&](double z_deg) { return sh::twinkle_airmass(static_cast<float>(std::cos(z_deg * deg))); };
    EXPECT_NEAR(at(0.0), 1.000, 0.005 * 1.000);
    EXPECT_NEAR(at(60.0), 1.995, 0.005 * 1.995);
    EXPECT_NEAR(at(80.0), 5.600, 0.005 * 5.600);
    EXPECT_NEAR(at(85.0), 10.32, 0.005 * 10.32);
    EXPECT_NEAR(at(90.0), 38.09, 0.005 * 38.09);
    EXPECT_EQ(sh::twinkle_airmass(-0.3f), sh::twinkle_airmass(0.0f));  // below the horizon: the horizon's
}

TEST(StarTwinkle, AmplitudeIsYoungsRelation) {
    // sqrt(1e-5 D^(-4/3) / t) for D = 7 mm, t = 0.1 s: 0.273 at sea level.
    const double expected = std::sqrt(1e-5 * std::pow(0.007, -4.0 / 3.0) / 0.1);
    EXPECT_NEAR(sh::twinkle_sigma_zenith(0.0f), expected, 1e-4);
    EXPECT_NEAR(expected, 0.273, 0.001);
    EXPECT_NEAR(sh::twinkle_sigma_zenith(2000.0f) / sh::twinkle_sigma_zenith(0.0f), std::exp(-0.25), 1e-5);
    EXPECT_NEAR(sh::twinkle_sigma(0.2f, 2.0f), 0.2 * std::pow(2.0, 1.5), 1e-5);
    EXPECT_FLOAT_EQ(sh::twinkle_sigma(0.273f, 10.0f), sh::TWINKLE_SIGMA_MAX);  // saturated
}

// What is rendered follows the model: over a minute, the factor's relative deviation is the
// model's sigma at each airmass (within 10 %, averaged over 40 stars), so the amplitude rises as
// X^1.5 up to the cap; its mean stays 1.
TEST(StarTwinkle, TheFactorsDeviationRisesWithAirmassAsTheModelSays) {
    const float sigma_zenith = sh::twinkle_sigma_zenith(0.0f);
    std::vector<double> xs, measured;
    for (double z_deg : {0.0, 30.0, 45.0, 55.0}) {
        const float x = sh::twinkle_airmass(static_cast<float>(std::cos(z_deg * M_PI / 180.0)));
        const float sigma = sh::twinkle_sigma(sigma_zenith, x);
        double dev = 0.0, mean = 0.0;
        for (unsigned star = 0; star < 40; ++star) {
            const auto [m, d] = factor_statistics(star, sigma);
            mean += m / 40.0;
            dev += d / 40.0;
        }
        std::printf("zenith %.0f deg: airmass %.3f, model sigma %.3f, measured %.3f, mean %.4f\n", z_deg, x, sigma, dev,
                    mean);
        EXPECT_NEAR(dev, sigma, 0.1 * sigma);
        EXPECT_NEAR(mean, 1.0, 0.03);
        xs.push_back(std::log(x));
        measured.push_back(std::log(dev));
    }
    const double slope = (measured.back() - measured.front()) / (xs.back() - xs.front());
    EXPECT_NEAR(slope, 1.5, 0.1);
}

TEST(StarTwinkle, TheSameStarAndClockGiveTheSameFactorOthersDiffer) {
    EXPECT_EQ(sh::twinkle_factor(17u, 3.25f, 0.3f), sh::twinkle_factor(17u, 3.25f, 0.3f));
    EXPECT_NE(sh::twinkle_factor(17u, 3.25f, 0.3f), sh::twinkle_factor(18u, 3.25f, 0.3f));
    EXPECT_NE(sh::twinkle_factor(17u, 3.25f, 0.3f), sh::twinkle_factor(17u, 3.30f, 0.3f));
    EXPECT_EQ(sh::twinkle_factor(17u, 3.25f, 0.0f), 1.0f);  // steady: exactly 1
}

TEST(StarTwinkle, ModesOnForcedAndOff) {
    Snapshot snap;
    snap.settings.twinkle_time_s = 12.5f;
    StarSky no_air;
    snap.settings.flags = with_twinkle_mode(0, TwinkleMode::Off);
    EXPECT_EQ(StarPass::twinkle_for(snap, no_air).sigma_zenith, 0.0f);
    snap.settings.flags = with_twinkle_mode(0, TwinkleMode::On);
    EXPECT_EQ(StarPass::twinkle_for(snap, no_air).sigma_zenith, 0.0f);  // no air, no twinkling
    snap.settings.flags = with_twinkle_mode(0, TwinkleMode::Forced);
    const StarTwinkle forced = StarPass::twinkle_for(snap, no_air);
    EXPECT_FLOAT_EQ(forced.sigma_zenith, sh::twinkle_sigma_zenith(0.0f));
    EXPECT_EQ(forced.zenith_world, glm::vec3(0.0f));  // every star as at the zenith
    EXPECT_EQ(forced.time_s, 12.5f);
    EXPECT_EQ(twinkle_mode_of(with_twinkle_mode(0xFFFFFFFFu, TwinkleMode::On)), TwinkleMode::On);
    EXPECT_EQ(twinkle_mode_of(0x3u << kTwinkleShift), TwinkleMode::Off);  // the unused value: steady
    EXPECT_EQ(twinkle_mode_from_name("forced"), TwinkleMode::Forced);
    EXPECT_THROW(twinkle_mode_from_name("sparkle"), std::invalid_argument);
}

// The display curve (shaders/shared/tone_curve.glsl, through shading:: and display_color()): the
// extended Reinhard operator on luminance, before the gamut map. Checked: no curve at a white of
// 0 (a fixed, calibration exposure); the curve's shape (slope 1 at black, white at W, monotonic,
// the identity when W = 1); the colour's chromaticity kept; highlights brought into the display
// at the colour's own hue, never clipped per channel; the inverse; and a PNG round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "image/frame_image.hpp"
#include "shading/shared_shading.hpp"
#include "support/test_support.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {
glm::vec3 chroma_direction(const glm::vec3& c) { return glm::normalize(c - glm::vec3(sh::rec709_luminance(c))); }
}  // namespace

TEST(ToneCurve, AWhiteOfZeroIsNoCurve) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> v(-1.0f, 50.0f);
    for (int i = 0; i < 1000; ++i) {
        const glm::vec3 c(v(rng), v(rng), v(rng));
        EXPECT_EQ(sh::tone_curve(c, 0.0f), c);
        EXPECT_EQ(display_color(c, 0.0), display_color(c));
    }
}

TEST(ToneCurve, SlopeOneAtBlackWhiteAtWMonotonicIdentityAtWOne) {
    for (float w : {1.0f, 2.0f, 8.0f, 100.0f}) {
        EXPECT_NEAR(sh::tone_curve_luminance(1e-6f, w) / 1e-6f, 1.0f, 1e-5f);
        EXPECT_NEAR(sh::tone_curve_luminance(w, w), 1.0f, 1e-6f);
        float last = 0.0f;
        for (float y = 0.001f; y < 2.0f * w; y *= 1.05f) {
            const float d = sh::tone_curve_luminance(y, w);
            EXPECT_GT(d, last) << "W " << w << " Y " << y;
            EXPECT_LE(d, y + 1e-6f) << "the curve never brightens";
            last = d;
        }
    }
    for (float y = 0.0f; y <= 1.0f; y += 0.01f) EXPECT_NEAR(sh::tone_curve_luminance(y, 1.0f), y, 1e-6f);
}

TEST(ToneCurve, KeepsChromaticityAndTheInverseUndoesIt) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> v(0.0f, 20.0f);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 c(v(rng), v(rng), v(rng));
        const float w = 4.0f;
        const glm::vec3 t = sh::tone_curve(c, w);
        const float y = sh::rec709_luminance(c), yt = sh::rec709_luminance(t);
        EXPECT_NEAR(yt, sh::tone_curve_luminance(y, w), 1e-5f * std::max(1.0f, y));
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(t[k] / yt, c[k] / y, 1e-4f * std::max(1.0f, c[k] / y));
        if (yt < 0.99f) {
            const glm::vec3 back = sh::tone_curve_inverse(t, w);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], c[k], 2e-4f * std::max(1.0f, c[k]));
        }
    }
}

// A saturated highlight (the sky by the Sun at sunset) is rolled off and brought into the cube
// along its own hue: the displayed colour's direction from its grey is the scene colour's, where
// clipping each channel would turn an orange toward yellow.
TEST(ToneCurve, HighlightsRollOffAtTheirOwnHueNeverClippedPerChannel) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> v(0.0f, 1.0f), scale(1.0f, 200.0f);
    int rolled = 0;
    for (int i = 0; i < 5000; ++i) {
        const glm::vec3 c = glm::vec3(v(rng), v(rng), v(rng)) * scale(rng);
        const glm::vec3 shown = display_color(c, 20.0);
        for (int k = 0; k < 3; ++k) ASSERT_TRUE(shown[k] >= 0.0f && shown[k] <= 1.0f);
        const float ys = sh::rec709_luminance(shown);
        if (ys > 0.999f || sh::rec709_luminance(c) < 1e-3f) continue;  // white: no hue left to keep
        EXPECT_NEAR(ys, std::min(1.0f, sh::tone_curve_luminance(sh::rec709_luminance(c), 20.0f)), 1e-4f);
        const glm::vec3 dc = chroma_direction(c), ds = chroma_direction(shown);
        EXPECT_GT(glm::dot(dc, ds), 0.9999f) << c.x << " " << c.y << " " << c.z;
        ++rolled;
    }
    EXPECT_GT(rolled, 1000);
    // Clipping per channel would have shifted this orange's hue; the curve does not.
    const glm::vec3 orange(40.0f, 12.0f, 1.0f);
    const glm::vec3 clipped = glm::clamp(orange * 0.05f, 0.0f, 1.0f);
    EXPECT_LT(glm::dot(chroma_direction(orange), chroma_direction(clipped)), 0.999f);
    EXPECT_GT(glm::dot(chroma_direction(orange), chroma_direction(display_color(orange, 20.0))), 0.9999f);
}

// A PNG records its white; reading it undoes the curve, so the radiance comes back within the
// 8-bit steps.
TEST(ToneCurve, APngRecordsItsWhiteAndReadsBackAsRadiance) {
    const std::string dir = test::scratch_dir("tone_curve_png");
    Image img;
    img.width = 16;
    img.height = 1;
    img.rgba.assign(16 * 4, 1.0f);
    for (int x = 0; x < 16; ++x)
        for (int k = 0; k < 3; ++k)
            img.rgba[4 * x + k] = 0.05f * std::pow(1.5f, static_cast<float>(x)) * (k == 0 ? 1.2f : 1.0f);
    FrameMetadata meta;
    meta.frame = 3;
    meta.tone_white = 8.0;
    meta.adapted_cd_m2 = 123.5;
    const auto paths = write_frame(dir, img, meta, {"png"}, 2.0);
    FrameMetadata back;
    const Image r = read_image_radiance(paths.at(0), &back);
    EXPECT_DOUBLE_EQ(back.tone_white, 8.0);
    EXPECT_DOUBLE_EQ(back.adapted_cd_m2, 123.5);
    for (int x = 0; x < 16; ++x) {
        const float y_exposed =
            2.0f * sh::rec709_luminance(glm::vec3(img.rgba[4 * x], img.rgba[4 * x + 1], img.rgba[4 * x + 2]));
        if (sh::tone_curve_luminance(y_exposed, 8.0f) > 0.9f) continue;  // flat near white: 8 bits say little
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(r.rgba[4 * x + k], img.rgba[4 * x + k], 0.03f * img.rgba[4 * x + k]) << x;
    }
}

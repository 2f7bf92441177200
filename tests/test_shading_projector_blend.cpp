// CPU tests of the projector blend functions (shaders/shared/projector_blend.glsl, compiled as
// C++ through common/shading/shared_shading.hpp; the warp pass runs the same text on the GPU and
// test_warp_pass compares the two).
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>

#include "image/frame_image.hpp"
#include "shading/shared_shading.hpp"

namespace sh = cupola::shading;

TEST(SharedProjectorBlend, BlendIsTheMpcdiRuleWithIntensity) {
    const sh::vec3 c(0.2f, 0.5f, 0.9f);
    const float alpha = 0.7f, intensity = 0.6f, beta = 0.05f;
    const sh::vec3 out = sh::projector_blend(c, alpha, intensity, beta);
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(out[k], c[k] * alpha * intensity * (1.0f - beta) + beta);
}

TEST(SharedProjectorBlend, BlackLiftKeepsWhiteAndRaisesBlack) {
    const float beta = 0.08f;
    EXPECT_FLOAT_EQ(sh::projector_black_lift(sh::vec3(0.0f), beta).x, beta);
    EXPECT_FLOAT_EQ(sh::projector_black_lift(sh::vec3(1.0f), beta).y, 1.0f);
    EXPECT_FLOAT_EQ(sh::projector_black_lift(sh::vec3(0.5f), 0.0f).z, 0.5f);
}

TEST(SharedProjectorBlend, ContentOutsideTheRangeIsMappedBeforeTheBlend) {
    // Above white and negative at once: mapped at constant luminance, then blended.
    const sh::vec3 c(1.6f, 0.45f, -0.3f);
    const float y = sh::rec709_luminance(c);
    const sh::vec3 out = sh::projector_blend(c, 0.5f, 1.0f, 0.0f);
    EXPECT_NEAR(sh::rec709_luminance(out), 0.5f * y, 1e-6);
    EXPECT_GE(std::min(out.x, std::min(out.y, out.z)), 0.0f);
    EXPECT_LE(std::max(out.x, std::max(out.y, out.z)), 0.5f + 1e-6f);
    // Above white everywhere: white, then blended.
    const sh::vec3 white = sh::projector_blend(sh::vec3(3.0f, 2.0f, 1.5f), 0.5f, 1.0f, 0.0f);
    EXPECT_FLOAT_EQ(white.x, 0.5f);
    EXPECT_FLOAT_EQ(white.z, 0.5f);
    // No luminance at all: black.
    EXPECT_FLOAT_EQ(sh::projector_blend(sh::vec3(3.0f, -1.0f, 1.0f), 0.5f, 1.0f, 0.0f).x, 0.0f);
}

TEST(SharedProjectorBlend, GammaEncodeAndDecodeAreInverse) {
    for (float gamma : {1.0f, 1.8f, 2.2f, 2.6f})
        for (float x = 0.0f; x <= 1.0f; x += 0.05f) {
            EXPECT_NEAR(sh::projector_gamma_decode(sh::projector_gamma_encode(x, gamma), gamma), x, 1e-5);
            EXPECT_NEAR(sh::projector_gamma_encode(x, gamma), std::pow(x, 1.0f / gamma), 1e-6);
        }
    EXPECT_FLOAT_EQ(sh::projector_gamma_encode(1.5f, 2.2f), 1.0f);  // clipped to the projector's range
}

TEST(SharedProjectorBlend, SrgbModeMatchesTheFrameWriterCurve) {
    for (float x = 0.0f; x <= 1.0f; x += 0.01f) {
        const sh::vec3 e = sh::projector_encode(sh::vec3(x), 2.2f, sh::PROJECTOR_ENCODE_SRGB);
        EXPECT_NEAR(e.x, cupola::linear_to_srgb(x), 1e-6) << x;
    }
    const sh::vec3 g = sh::projector_encode(sh::vec3(0.25f), 2.0f, sh::PROJECTOR_ENCODE_GAMMA);
    EXPECT_NEAR(g.x, 0.5f, 1e-6);
}

// The eye's night vision (shaders/shared/night_vision.glsl): the CIE 191:2010 mesopic coefficient
// against the system's own equation and end points, and a grey-card scene shown at adaptation
// luminances 100, 1, 0.01 and 0.001 cd/m^2 through the CPU display transform (PNG) and the GPU
// warp pass (projectors): the share of the cones recovered from the shown colour follows CIE's m,
// the hue moves to the rods' blue, a red card darkens and a blue one brightens (Purkinje).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "gl/gl_texture.hpp"
#include "image/frame_image.hpp"
#include "output/warp_pass.hpp"
#include "shading/shared_shading.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {

// CIE 191:2010, MES2 (section 3): m = a + b log10(L_mes), a = 0.7670, b = 0.3334, in [0, 1].
double cie_m(double l_mes_cd_m2) { return std::clamp(0.7670 + 0.3334 * std::log10(l_mes_cd_m2), 0.0, 1.0); }

glm::dvec2 chromaticity(glm::dvec3 rgb) {
    const glm::dvec3 xyz(0.4124 * rgb.r + 0.3576 * rgb.g + 0.1805 * rgb.b,
                         0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b,
                         0.0193 * rgb.r + 0.1192 * rgb.g + 0.9505 * rgb.b);
    const double s = xyz.x + xyz.y + xyz.z;
    return glm::dvec2(xyz.x / s, xyz.y / s);
}

// The cones' share in a grey card's shown colour: the colour is m white + (1 - m) blue (times its
// luminance), so m is the projection of shown / Y - blue on white - blue.
double cone_share_of_grey(glm::dvec3 shown) {
    const glm::dvec3 blue(sh::NIGHT_ROD_BLUE);
    const double y = sh::rec709_luminance(glm::vec3(shown));
    const glm::dvec3 d = shown / y - blue, axis = glm::dvec3(1.0) - blue;
    return glm::dot(d, axis) / glm::dot(axis, axis);
}

constexpr double kLevels[] = {100.0, 1.0, 0.01, 0.001};
constexpr double kKey = 0.18;  // the card is shown at this display level: exposure = key / L

}  // namespace

TEST(NightVision, TheConesShareFollowsTheCieMesopicSystem) {
    EXPECT_EQ(sh::mesopic_cone_share(5.0f), 1.0f);  // photopic at 5 cd/m^2 and above
    EXPECT_EQ(sh::mesopic_cone_share(1e4f), 1.0f);
    EXPECT_EQ(sh::mesopic_cone_share(0.005f), 0.0f);  // scotopic at 0.005 and below
    EXPECT_EQ(sh::mesopic_cone_share(0.0f), 0.0f);
    float last = -1.0f;
    for (double l = 0.004; l < 6.0; l *= 1.3) {
        const float m = sh::mesopic_cone_share(static_cast<float>(l));
        EXPECT_NEAR(m, cie_m(l), 1e-5) << l;
        EXPECT_GE(m, last) << l;
        last = m;
    }
    EXPECT_NEAR(sh::mesopic_cone_share(1.0f), 0.7670, 1e-6);
    EXPECT_NEAR(sh::mesopic_cone_share(0.1f), 0.4336, 1e-5);
}

TEST(NightVision, TheRodsSeeTheD65WhiteAtItsLuminanceAndBlueAboveRed) {
    EXPECT_NEAR(sh::rod_luminance(glm::vec3(1.0f)), 1.0f, 1e-4);
    EXPECT_NEAR(sh::rec709_luminance(sh::NIGHT_ROD_BLUE), 1.0f, 1e-3);
    const glm::dvec2 b = chromaticity(glm::dvec3(sh::NIGHT_ROD_BLUE));
    EXPECT_NEAR(b.x, 0.25, 1e-4);
    EXPECT_NEAR(b.y, 0.25, 1e-4);
    const glm::vec3 red(1.0f, 0.05f, 0.05f), blue(0.05f, 0.1f, 1.0f);
    EXPECT_LT(sh::rod_luminance(red), 0.5f * sh::rec709_luminance(red));
    EXPECT_GT(sh::rod_luminance(blue), 2.0f * sh::rec709_luminance(blue));
    EXPECT_EQ(sh::night_vision(red, 1.0f, 0.0f), red);  // off
}

TEST(NightVision, AGreyCardFadesToTheRodsBlueAsCieSaysOnTheCpu) {
    for (double l : kLevels) {
        const double exposure = kKey / l;
        const glm::vec3 card = glm::vec3(static_cast<float>(l)) * static_cast<float>(exposure);
        const glm::dvec3 shown(display_color(card, 0.0, exposure, l));
        const double m = cone_share_of_grey(shown);
        std::printf("grey card at %g cd/m^2: cone share %.4f (CIE %.4f), xy (%.4f, %.4f), level %.4f\n", l, m, cie_m(l),
                    chromaticity(shown).x, chromaticity(shown).y, sh::rec709_luminance(glm::vec3(shown)));
        EXPECT_NEAR(m, cie_m(l), 0.01) << l;
        EXPECT_NEAR(sh::rec709_luminance(glm::vec3(shown)), kKey, 2e-3) << l;  // a grey keeps its level
    }
    const glm::dvec2 day = chromaticity(glm::dvec3(display_color(glm::vec3(0.18f), 0.0, 0.0018, 100.0)));
    EXPECT_NEAR(day.x, 0.3127, 1e-3);
    EXPECT_NEAR(day.y, 0.3290, 1e-3);
}

TEST(NightVision, RedDarkensBlueBrightensAndABrightPointKeepsItsColour) {
    const glm::vec3 red(0.5f, 0.03f, 0.03f), blue(0.03f, 0.06f, 0.5f);
    const double l = 0.001, exposure = 1e-3;  // cards at a luminance where only the rods see
    const glm::vec3 r =
        display_color(red * static_cast<float>(l / sh::rec709_luminance(red) * exposure), 0.0, exposure, l);
    const glm::vec3 b =
        display_color(blue * static_cast<float>(l / sh::rec709_luminance(blue) * exposure), 0.0, exposure, l);
    EXPECT_LT(sh::rec709_luminance(r), 0.5 * l * exposure);
    EXPECT_GT(sh::rec709_luminance(b), 2.0 * l * exposure);
    // A point of 50 cd/m^2 in a sky the eye is adapted to at 0.001: the cones see it, in colour.
    const glm::vec3 star = red * static_cast<float>(50.0 / sh::rec709_luminance(red) * exposure);
    EXPECT_EQ(display_color(star, 0.0, exposure, l), display_color(star, 0.0));
}

TEST(NightVision, TheWarpPassShowsTheCardLikeThePng) {
    test::headless_gl();
    for (double l : kLevels) {
        const double exposure = kKey / l;
        // Three patches side by side: grey, red and blue, at the adapted luminance.
        const glm::vec3 patches[3] = {glm::vec3(1.0f), glm::vec3(0.9f, 0.3f, 0.2f), glm::vec3(0.2f, 0.3f, 0.9f)};
        std::vector<glm::vec4> texels;
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 12; ++x) {
                const glm::vec3 c = patches[x / 4];
                texels.emplace_back(c * static_cast<float>(l / sh::rec709_luminance(c)), 1.0f);
            }
        const GlTexture content(12, 4, texels.data(), GL_NEAREST);
        WarpPass pass(std::nullopt, 12, 4);
        pass.draw(content.id(), exposure, 0.0, l);
        const Image lin = pass.read_linear();
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 gpu(lin.pixel(4 * k + 2, 2)[0], lin.pixel(4 * k + 2, 2)[1], lin.pixel(4 * k + 2, 2)[2]);
            const glm::vec3 cpu =
                display_color(glm::vec3(texels[4 * k + 2]) * static_cast<float>(exposure), 0.0, exposure, l);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[c], cpu[c], 2e-3 * std::max(1.0f, cpu[c])) << l << " " << k;
        }
        const glm::dvec3 grey(lin.pixel(2, 2)[0], lin.pixel(2, 2)[1], lin.pixel(2, 2)[2]);
        EXPECT_NEAR(cone_share_of_grey(grey), cie_m(l), 0.01) << l;
    }
}

TEST(NightVision, APngRecordsNightVisionAndShowsWhatTheEyeSaw) {
    const std::string dir = test::scratch_dir("night_vision_png");
    Image img;
    img.width = 2;
    img.height = 1;
    img.rgba = {0.01f, 0.01f, 0.01f, 1.0f, 0.01f, 0.01f, 0.01f, 1.0f};
    FrameMetadata meta;
    meta.frame = 3;
    meta.adapted_cd_m2 = 0.01;
    meta.night_vision = true;
    const auto paths = write_frame(dir, img, meta, {"png", "exr"}, 18.0);
    FrameMetadata back, back_exr;
    const Image shown = read_image(paths[0], &back);
    read_image(paths[1], &back_exr);
    EXPECT_TRUE(back.night_vision);
    EXPECT_TRUE(back_exr.night_vision);
    EXPECT_DOUBLE_EQ(back.night_adapted_cd_m2(), 0.01);
    // The grey read back from the PNG is bluish (the eye's), the EXR's is still grey (physical).
    EXPECT_GT(shown.pixel(0, 0)[2], shown.pixel(0, 0)[0] * 1.2f);
    meta.night_vision = false;
    const auto off = write_frame(dir + "/off", img, meta, {"png"}, 18.0);
    const Image grey = read_image(off[0], &back);
    EXPECT_FALSE(back.night_vision);
    EXPECT_NEAR(grey.pixel(0, 0)[2], grey.pixel(0, 0)[0], 2e-4);
}

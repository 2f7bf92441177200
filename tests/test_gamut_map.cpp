// The gamut map of the PNG path (shaders/shared/gamut_map.glsl through display_color(),
// common/image/frame_image.hpp): colours outside the unit cube, with negative or above-1
// components (linear sRGB below the horizon at sunset has a negative blue), reach the PNG as
// mapped, non-negative values of the same luminance and dominant wavelength; colours inside are
// unchanged; the EXR keeps the scene-linear values, negative ones included.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "image/frame_image.hpp"
#include "shading/shared_shading.hpp"
#include "support/test_support.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// The chromaticity direction from the white: (c - Y) / |c - Y|, the line the map moves along.
glm::vec3 chroma_direction(const glm::vec3& c) { return glm::normalize(c - glm::vec3(luminance(c))); }

// The range of linear values an 8-bit sRGB code stands for (half a code either side).
float decoded_lo(int code) { return srgb_to_linear(std::max(0.0f, (code - 0.5f) / 255.0f)); }
float decoded_hi(int code) { return srgb_to_linear(std::min(1.0f, (code + 0.5f) / 255.0f)); }

}  // namespace

TEST(GamutMap, InsideUnchangedOutsideMappedAtConstantLuminanceAndHue) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> inside(0.0f, 1.0f), wide(-0.6f, 1.8f);
    int outside_seen = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 in(inside(rng), inside(rng), inside(rng));
        EXPECT_EQ(sh::gamut_map_to_unit_cube(in), in);
        const glm::vec3 c(wide(rng), wide(rng), wide(rng));
        const glm::vec3 m = sh::gamut_map_to_unit_cube(c);
        for (int k = 0; k < 3; ++k) {
            ASSERT_GE(m[k], 0.0f) << c.x << " " << c.y << " " << c.z;
            ASSERT_LE(m[k], 1.0f);
        }
        const float y = luminance(c);
        const bool out = std::min({c.x, c.y, c.z}) < 0.0f || std::max({c.x, c.y, c.z}) > 1.0f;
        if (!out || y <= 0.01f || y >= 0.99f) continue;
        ++outside_seen;
        EXPECT_NEAR(luminance(m), y, 2e-6f);                                     // luminance kept
        EXPECT_GT(glm::dot(chroma_direction(m), chroma_direction(c)), 0.9999f);  // same dominant wavelength
        // On the cube's surface: the least saturated change that fits.
        EXPECT_TRUE(std::min({m.x, m.y, m.z}) < 1e-6f || std::max({m.x, m.y, m.z}) > 1.0f - 1e-6f);
    }
    EXPECT_GT(outside_seen, 5000);
    EXPECT_EQ(sh::gamut_map_to_unit_cube(glm::vec3(3.0f, 0.6f, -0.2f)), glm::vec3(1.0f));  // luminance > 1: white
    EXPECT_EQ(sh::gamut_map_to_unit_cube(glm::vec3(0.1f, -0.2f, 0.3f)), glm::vec3(0.0f));  // luminance < 0: black
}

// An image with negative and above-1 components, written as PNG: every code comes from the mapped
// colour, whose luminance is the original's where that is representable; a per-channel clip
// would brighten the first pixel by 30 % (its negative blue clipped to 0 adds luminance).
TEST(GamutMap, PngPixelsComeFromMappedNonNegativeValues) {
    const std::vector<glm::vec3> colours = {
        {0.05f, 0.2f, -0.5f},    // sunset below the horizon: negative blue
        {0.30f, 0.12f, -0.04f},  // slightly negative
        {1.4f, 0.5f, 0.2f},      // above 1, luminance below 1
        {1.6f, 0.45f, -0.3f},    // both at once
        {0.2f, 0.4f, 0.6f},      // inside: unchanged
        {0.9f, 0.01f, 0.5f},     // inside
        {2.0f, 3.0f, 1.5f},      // luminance above 1: white
        {-0.2f, 0.01f, 0.02f},   // luminance below 0: black
    };
    Image im;
    im.width = static_cast<int>(colours.size());
    im.height = 1;
    for (const glm::vec3& c : colours) im.rgba.insert(im.rgba.end(), {c.x, c.y, c.z, 1.0f});
    const std::string dir = test::scratch_dir("gamut_map_png");
    FrameMetadata meta;
    meta.frame = 3;
    const auto paths = write_frame(dir, im, meta, {"png", "exr"}, 1.0);
    auto in = OIIO::ImageInput::open(paths[0]);
    ASSERT_TRUE(in);
    std::vector<uint8_t> px(colours.size() * 4);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
    for (size_t i = 0; i < colours.size(); ++i) {
        const glm::vec3 c = colours[i];
        const glm::vec3 mapped = display_color(c);
        glm::vec3 lo(0.0f), hi(0.0f);
        for (int k = 0; k < 3; ++k) {
            const int code = px[i * 4 + k];
            EXPECT_EQ(code, std::lround(linear_to_srgb(mapped[k]) * 255.0f)) << "pixel " << i << " channel " << k;
            lo[k] = decoded_lo(code);
            hi[k] = decoded_hi(code);
            EXPECT_GE(mapped[k], 0.0f);
        }
        const float y = luminance(c);
        const bool inside = std::min({c.x, c.y, c.z}) >= 0.0f && std::max({c.x, c.y, c.z}) <= 1.0f;
        if (inside) {
            for (int k = 0; k < 3; ++k) EXPECT_EQ(mapped[k], c[k]);
        }
        if (y > 0.0f && y < 1.0f) {  // representable: the PNG's luminance is the original's
            EXPECT_LE(luminance(lo), y) << "pixel " << i;
            EXPECT_GE(luminance(hi), y) << "pixel " << i;
        }
    }
    const glm::vec3 clipped = glm::clamp(colours[0], 0.0f, 1.0f);
    EXPECT_GT(luminance(clipped), 1.25f * luminance(colours[0]));  // what the map avoids
    // The EXR stays scene-linear: the negative blue is kept.
    const Image exr = read_image(paths[1]);
    EXPECT_FLOAT_EQ(exr.pixel(0, 0)[2], -0.5f);
    EXPECT_FLOAT_EQ(exr.pixel(2, 0)[0], 1.4f);
}

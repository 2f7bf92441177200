// Body maps as the body pass and the atmosphere take them (slave/passes/body_texture.hpp): real
// files written here with OpenImageIO, every 8-bit value decoded from sRGB exactly as the 16-bit
// (float) path decodes the same value (within a millionth), and the generated surface deterministic and cratered.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "passes/body_texture.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

// IEC 61966-2-1, written out here: the linear value of an encoded one in [0, 1].
float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// A 256 x 1 image holding every 8-bit value, in `channels` channels (the channels shifted by 85).
template <typename T>
std::string write_ramp(const std::string& dir, const std::string& name, int channels, OIIO::TypeDesc type) {
    const std::string path = dir + "/" + name;
    std::vector<T> px(256 * static_cast<size_t>(channels));
    const double scale = (std::pow(2.0, 8.0 * sizeof(T)) - 1.0) / 255.0;  // 1 for bytes, 257 for 16 bits
    for (int k = 0; k < 256; ++k)
        for (int c = 0; c < channels; ++c) px[k * channels + c] = static_cast<T>(((k + 85 * c) % 256) * scale);
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(256, 1, channels, type)));
    EXPECT_TRUE(out->write_image(type, px.data()));
    out->close();
    return path;
}

}  // namespace

TEST(BodyTexture, EveryEightBitValueIsDecodedFromSrgbAsTheSixteenBitPathDecodesIt) {
    const std::string dir = test::scratch_dir("body_texture_ramp");
    const BodyImage bytes = load_body_image(write_ramp<uint8_t>(dir, "ramp8.png", 3, OIIO::TypeDesc::UINT8));
    const BodyImage words = load_body_image(write_ramp<uint16_t>(dir, "ramp16.png", 3, OIIO::TypeDesc::UINT16));
    ASSERT_EQ(bytes.width, 256);
    ASSERT_EQ(bytes.height, 1);
    ASSERT_EQ(bytes.rgb.size(), words.rgb.size());
    for (int k = 0; k < 256; ++k)
        for (int c = 0; c < 3; ++c) {
            const float want = srgb_to_linear(static_cast<float>((k + 85 * c) % 256) / 255.0f);
            // Within a few float steps: OpenImageIO scales a byte by 1/255 in float, which is not
            // always the correctly rounded k / 255.
            EXPECT_NEAR(bytes.rgb[k * 3 + c], want, 1e-6f * want) << "value " << (k + 85 * c) % 256;
            EXPECT_NEAR(bytes.rgb[k * 3 + c], words.rgb[k * 3 + c], 1e-6f * want) << "value " << (k + 85 * c) % 256;
        }
}

TEST(BodyTexture, AGreyMapFillsAllThreeChannels) {
    const std::string dir = test::scratch_dir("body_texture_grey");
    const BodyImage grey = load_body_image(write_ramp<uint8_t>(dir, "grey.png", 1, OIIO::TypeDesc::UINT8));
    for (int k = 0; k < 256; ++k) {
        EXPECT_EQ(grey.rgb[k * 3], grey.rgb[k * 3 + 1]);
        EXPECT_EQ(grey.rgb[k * 3], grey.rgb[k * 3 + 2]);
        EXPECT_NEAR(grey.rgb[k * 3], srgb_to_linear(k / 255.0f), 1e-6f * srgb_to_linear(k / 255.0f));
    }
}

TEST(BodyTexture, AMissingFileIsNamed) {
    try {
        load_body_image("/nonexistent/map.jpg");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/map.jpg"), std::string::npos) << e.what();
    }
}

TEST(BodyTexture, TheGeneratedSurfaceIsDeterministicAndCratered) {
    const BodyImage a = load_body_image("generated:moon"), b = load_body_image("generated:moon");
    const BodyImage other = load_body_image("generated:io");
    ASSERT_EQ(a.width, 512);
    ASSERT_EQ(a.height, 256);
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_NE(a.rgb, other.rgb);
    const auto [lo, hi] = std::minmax_element(a.rgb.begin(), a.rgb.end());
    EXPECT_GE(*lo, 0.0f);
    EXPECT_LE(*hi, 1.0f);
    EXPECT_GT(*hi - *lo, 0.2f);  // floors and bright rims, not a flat grey
}

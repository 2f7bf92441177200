// The body maps' mipmap chain built on the CPU (common/image/mip_chain.hpp): each level the area
// mean of the one above, odd sizes included, and bad input named.
#include <gtest/gtest.h>

#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "image/mip_chain.hpp"

using namespace cupola;

namespace {

std::vector<float> random_image(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> d(0.0f, 4.0f);
    std::vector<float> rgb(static_cast<size_t>(w) * h * 3);
    for (auto& v : rgb) v = d(rng);
    return rgb;
}

// The sum of one channel times the texel's area in level-0 texels: the light a level carries.
double light(const std::vector<float>& rgb, int w, int h, int channel, int w0, int h0) {
    double s = 0.0;
    for (size_t i = static_cast<size_t>(channel); i < rgb.size(); i += 3) s += rgb[i];
    return s * (static_cast<double>(w0) / w) * (static_cast<double>(h0) / h);
}

}  // namespace

TEST(MipChain, EvenLevelsAreTheMeanOfEachTwoByTwoBlock) {
    const int w = 8, h = 4;
    const auto rgb = random_image(w, h, 1);
    const auto chain = box_filter_mip_chain(w, h, rgb);
    ASSERT_EQ(chain.size(), 3u);  // 4x2, 2x1, 1x1
    EXPECT_EQ(chain[0].width, 4);
    EXPECT_EQ(chain[0].height, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) {
                auto at = [&](int xx, int yy) { return rgb[(static_cast<size_t>(yy) * w + xx) * 3 + c]; };
                const float want =
                    0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1));
                EXPECT_FLOAT_EQ(chain[0].texels[(static_cast<size_t>(y) * 4 + x) * 3 + c], want);
            }
    EXPECT_EQ(chain[2].width, 1);
    EXPECT_EQ(chain[2].height, 1);
}

TEST(MipChain, EveryLevelOfAnOddSizedImageCarriesTheSameLight) {
    // 13 x 7 -> 6 x 3 -> 3 x 1 -> 1 x 1: every level keeps the image's mean to float rounding.
    const int w = 13, h = 7;
    const auto rgb = random_image(w, h, 2);
    const auto chain = box_filter_mip_chain(w, h, rgb);
    ASSERT_EQ(chain.size(), 3u);
    EXPECT_EQ(chain[0].width, 6);
    EXPECT_EQ(chain[0].height, 3);
    EXPECT_EQ(chain[1].width, 3);
    EXPECT_EQ(chain[1].height, 1);
    for (int c = 0; c < 3; ++c) {
        const double want = light(rgb, w, h, c, w, h);
        for (const auto& l : chain) EXPECT_NEAR(light(l.texels, l.width, l.height, c, w, h), want, 1e-5 * want);
    }
}

TEST(MipChain, AUniformImageStaysUniformAtEveryLevel) {
    const int w = 11, h = 6;
    const std::vector<float> rgb(static_cast<size_t>(w) * h * 3, 0.37f);
    for (const auto& l : box_filter_mip_chain(w, h, rgb))
        for (float v : l.texels) EXPECT_NEAR(v, 0.37f, 1e-6f);
}

TEST(MipChain, AOneTexelImageHasNoFurtherLevel) { EXPECT_TRUE(box_filter_mip_chain(1, 1, {0.1f, 0.2f, 0.3f}).empty()); }

TEST(MipChain, ATallImageEndsAtOneByOne) {
    const auto chain = box_filter_mip_chain(1, 5, random_image(1, 5, 3));
    ASSERT_EQ(chain.size(), 2u);  // 1x2, 1x1
    EXPECT_EQ(chain.back().width, 1);
    EXPECT_EQ(chain.back().height, 1);
}

TEST(MipChain, BadInputIsNamed) {
    try {
        box_filter_mip_chain(4, 4, std::vector<float>(47));
        FAIL() << "a short image was taken";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("4x4 RGB image needs 48 floats, got 47"), std::string::npos) << e.what();
    }
    EXPECT_THROW(box_filter_mip_chain(0, 4, {}), std::invalid_argument);
    EXPECT_THROW(box_filter_mip_chain(-2, 4, {}), std::invalid_argument);
}

TEST(MipChain, OneChannelCoverageKeepsItsMeanAndMatchesTheRgbChainsRed) {
    // A glyph atlas has one channel: its chain is the RGB chain's red, texel for texel.
    const int w = 13, h = 6;
    const auto rgb = random_image(w, h, 4);
    std::vector<float> red(static_cast<size_t>(w) * h);
    for (size_t i = 0; i < red.size(); ++i) red[i] = rgb[3 * i];
    const auto grey = box_filter_mip_chain(w, h, red, 1);
    const auto colour = box_filter_mip_chain(w, h, rgb);
    ASSERT_EQ(grey.size(), colour.size());
    for (size_t l = 0; l < grey.size(); ++l) {
        EXPECT_EQ(grey[l].channels, 1);
        ASSERT_EQ(grey[l].texels.size() * 3, colour[l].texels.size()) << "level " << l + 1;
        for (size_t i = 0; i < grey[l].texels.size(); ++i)
            EXPECT_FLOAT_EQ(grey[l].texels[i], colour[l].texels[3 * i]) << "level " << l + 1 << " texel " << i;
    }
    try {
        box_filter_mip_chain(4, 4, std::vector<float>(15), 1);
        FAIL() << "a short coverage image was taken";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("4x4 1-channel image needs 16 floats, got 15"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(box_filter_mip_chain(2, 2, std::vector<float>(20), 5), std::invalid_argument);
}

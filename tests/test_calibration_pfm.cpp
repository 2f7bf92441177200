// PFM warp files (common/calibration/pfm_file): both channel counts, both byte orders (the scale's
// sign), both row orders, NaN points, and the errors on bad files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "calibration/calibration_error.hpp"
#include "calibration/pfm_file.hpp"

using namespace cupola;

namespace {

PfmImage ramp(int w, int h, int channels) {
    PfmImage img{w, h, channels, std::vector<float>(static_cast<size_t>(w) * h * channels)};
    for (size_t k = 0; k < img.data.size(); ++k) img.data[k] = 0.25f * static_cast<float>(k) - 3.0f;
    return img;
}

std::string expect_error(const std::string& bytes, const std::string& field_part) {
    try {
        decode_pfm(bytes, "warp.pfm", PfmRows::bottom_first);
    } catch (const CalibrationError& e) {
        EXPECT_EQ(e.file(), "warp.pfm");
        EXPECT_NE(std::string(e.what()).find(field_part), std::string::npos) << e.what();
        return e.what();
    }
    ADD_FAILURE() << "no error for a bad PFM (" << field_part << ")";
    return {};
}

}  // namespace

TEST(CalibrationPfm, RoundTripsEveryLayout) {
    for (int channels : {1, 3})
        for (PfmRows rows : {PfmRows::bottom_first, PfmRows::top_first})
            for (PfmByteOrder order : {PfmByteOrder::little_endian, PfmByteOrder::big_endian}) {
                const PfmImage img = ramp(5, 3, channels);
                const PfmImage back = decode_pfm(encode_pfm(img, rows, order), "x.pfm", rows);
                EXPECT_EQ(back.width, 5);
                EXPECT_EQ(back.height, 3);
                EXPECT_EQ(back.channels, channels);
                EXPECT_EQ(back.data, img.data);
            }
}

TEST(CalibrationPfm, ScaleSignGivesTheByteOrder) {
    // A big-endian file written by hand: positive scale, most significant byte first.
    std::string be = "Pf\n2 1\n1.0\n";
    for (float f : {1.5f, -2.0f}) {
        uint32_t w;
        std::memcpy(&w, &f, 4);
        for (int s = 24; s >= 0; s -= 8) be.push_back(static_cast<char>((w >> s) & 0xff));
    }
    const PfmImage img = decode_pfm(be, "be.pfm", PfmRows::top_first);
    EXPECT_EQ(img.data, (std::vector<float>{1.5f, -2.0f}));
    // The same bytes with a negative scale read as little-endian: different numbers.
    std::string le = be;
    le.replace(le.find("1.0"), 3, "-1.0");
    EXPECT_NE(decode_pfm(le, "le.pfm", PfmRows::top_first).data, img.data);
}

TEST(CalibrationPfm, RowOrderSwitchFlipsTheRows) {
    const PfmImage img = ramp(2, 3, 1);
    const std::string bytes = encode_pfm(img, PfmRows::bottom_first, PfmByteOrder::little_endian);
    const PfmImage as_top = decode_pfm(bytes, "x.pfm", PfmRows::top_first);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 2; ++x) EXPECT_EQ(as_top.at(x, y, 0), img.at(x, 2 - y, 0));
    // bottom-first: the file's first row is the raster's bottom row.
    float first;
    std::memcpy(&first, bytes.data() + bytes.size() - 6 * 4, 4);
    EXPECT_EQ(first, img.at(0, 2, 0));
}

TEST(CalibrationPfm, NanPointsSurvive) {
    PfmImage img = ramp(2, 2, 3);
    img.data[3] = std::numeric_limits<float>::quiet_NaN();
    const PfmImage back =
        decode_pfm(encode_pfm(img, PfmRows::top_first, PfmByteOrder::big_endian), "x.pfm", PfmRows::top_first);
    EXPECT_TRUE(std::isnan(back.data[3]));
    EXPECT_EQ(back.data[4], img.data[4]);
}

TEST(CalibrationPfm, BadFilesNameTheField) {
    expect_error("", "PFM magic");
    expect_error("P6\n2 2\n255\n", "PFM magic");
    expect_error("PF\n-2 2\n-1.0\n", "PFM width");
    expect_error("PF\n2 x\n-1.0\n", "PFM height");
    expect_error("PF\n2 2\nabc\n", "PFM scale");
    expect_error("PF\n2 2\n0\n", "PFM scale");
    expect_error("PF\n2 2\n-1.0\n" + std::string(47, '\0'), "need 48 bytes");
    expect_error("PF\n100000 100000\n-1.0\n", "PFM data");
    expect_error("PF\n2 2", "PFM");
}

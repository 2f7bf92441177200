// Frame files: PNG (8-bit sRGB) and EXR (32-bit float, linear) written with metadata and read back.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "image/frame_image.hpp"
#include "support/test_support.hpp"

namespace fs = std::filesystem;
using namespace cupola;

namespace {

Image gradient_image(int w, int h) {
    Image im;
    im.width = w;
    im.height = h;
    im.rgba.resize(static_cast<size_t>(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = im.pixel(x, y);
            p[0] = static_cast<float>(x) / (w - 1);                      // 0..1
            p[1] = static_cast<float>(y) / (h - 1) * 0.5f;               // 0..0.5
            p[2] = 0.001f + 3.0f * static_cast<float>(x * y) / (w * h);  // beyond 1: gamut-mapped in PNG
            p[3] = (x + y) % 3 == 0 ? 1.0f : 0.5f;
        }
    return im;
}

FrameMetadata sample_meta() {
    FrameMetadata m;
    m.channel_id = 3;
    m.channel_name = "left-wall";
    m.frame = 42;
    m.sim_time_s = 7.3e8 + 0.123456789012345;
    m.snapshot_hash = "0123456789abcdef";
    m.renderer = "llvmpipe (LLVM 15.0.7, 256 bits)";
    return m;
}

void expect_meta_eq(const FrameMetadata& a, const FrameMetadata& b) {
    EXPECT_EQ(a.channel_id, b.channel_id);
    EXPECT_EQ(a.channel_name, b.channel_name);
    EXPECT_EQ(a.frame, b.frame);
    EXPECT_EQ(a.sim_time_s, b.sim_time_s);  // %.17g round-trips a double exactly
    EXPECT_EQ(a.snapshot_hash, b.snapshot_hash);
    EXPECT_EQ(a.renderer, b.renderer);
}

}  // namespace

TEST(FrameImage, FileNames) {
    EXPECT_EQ(frame_file_name(42, "png"), "frame_000042.png");
    EXPECT_EQ(frame_file_name(0, "exr"), "frame_000000.exr");
    EXPECT_EQ(frame_file_name(1234567, "png"), "frame_1234567.png");
}

TEST(FrameImage, SrgbTransfer) {
    EXPECT_NEAR(linear_to_srgb(0.0f), 0.0f, 1e-7);
    EXPECT_NEAR(linear_to_srgb(1.0f), 1.0f, 1e-6);
    EXPECT_NEAR(linear_to_srgb(0.18f), 0.461356f, 1e-5);  // the sRGB curve at 18% grey
    EXPECT_NEAR(linear_to_srgb(5.0f), 1.0f, 1e-6);        // clamped
    for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(srgb_to_linear(linear_to_srgb(v)), v, 1e-5);
}

TEST(FrameImage, WritesPngAndExrWithMetadataAndReadsThemBack) {
    const std::string dir = test::scratch_dir("frame_image_roundtrip") + "/out/nested";
    const Image im = gradient_image(37, 23);
    const FrameMetadata meta = sample_meta();
    const double exposure = 2.0;
    const auto paths = write_frame(dir, im, meta, {"png", "exr"}, exposure);
    ASSERT_EQ(paths.size(), 2u);
    EXPECT_EQ(fs::path(paths[0]).filename(), "frame_000042.png");
    EXPECT_EQ(fs::path(paths[1]).filename(), "frame_000042.exr");
    // No temporary file is left behind.
    int entries = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        (void)e;
        ++entries;
    }
    EXPECT_EQ(entries, 2);

    FrameMetadata exr_meta, png_meta;
    const Image exr = read_image(paths[1], &exr_meta);
    const Image png = read_image(paths[0], &png_meta);
    expect_meta_eq(exr_meta, meta);
    expect_meta_eq(png_meta, meta);
    ASSERT_EQ(exr.width, im.width);
    ASSERT_EQ(exr.height, im.height);
    ASSERT_EQ(png.width, im.width);
    ASSERT_EQ(png.height, im.height);

    const Image exr_radiance = read_image_radiance(paths[1]);
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            const float* s = im.pixel(x, y);
            const float* e = exr.pixel(x, y);
            const float* r = exr_radiance.pixel(x, y);
            const float* p = png.pixel(x, y);
            const glm::vec3 shown = display_color(glm::vec3(s[0], s[1], s[2]) * static_cast<float>(exposure));
            for (int c = 0; c < 3; ++c) {
                const float exposed = static_cast<float>(s[c] * exposure);
                // EXR: linear times exposure, in float.
                EXPECT_FLOAT_EQ(e[c], exposed) << x << "," << y << "," << c;
                EXPECT_NEAR(r[c], s[c], std::abs(s[c]) * 1e-6 + 1e-12);
                // PNG: decoded and divided by the recorded exposure; the exposed colour is mapped into
                // the unit cube (test_gamut_map checks how).
                const float enc = linear_to_srgb(shown[c]);
                // One 8-bit step of sRGB around the encoded value, back in linear, over the exposure.
                const float lo = srgb_to_linear(enc - 0.5f / 255 - 1e-6f) / static_cast<float>(exposure);
                const float hi = srgb_to_linear(enc + 0.5f / 255 + 1e-6f) / static_cast<float>(exposure);
                EXPECT_GE(p[c], lo) << x << "," << y << "," << c;
                EXPECT_LE(p[c], hi) << x << "," << y << "," << c;
            }
            EXPECT_NEAR(e[3], s[3], 1e-3);  // alpha is not exposed
            EXPECT_NEAR(p[3], s[3], 0.5 / 255 + 1e-6);
        }

    // The file itself: EXR is float RGBA, PNG is 8-bit RGBA.
    auto in = OIIO::ImageInput::open(paths[1]);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(in->spec().nchannels, 4);
    in->close();
    in = OIIO::ImageInput::open(paths[0]);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
    EXPECT_EQ(in->spec().nchannels, 4);
    in->close();
}

TEST(FrameImage, RowZeroIsTheTopRow) {
    const std::string dir = test::scratch_dir("frame_image_rows");
    Image im;
    im.width = 4;
    im.height = 3;
    im.rgba.assign(4 * 3 * 4, 0.0f);
    for (int x = 0; x < 4; ++x) im.pixel(x, 0)[0] = 1.0f, im.pixel(x, 0)[3] = 1.0f;
    const auto paths = write_frame(dir, im, {}, {"png"}, 1.0);
    auto in = OIIO::ImageInput::open(paths[0]);
    ASSERT_TRUE(in);
    std::vector<unsigned char> px(4 * 3 * 4);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
    EXPECT_EQ(px[0], 255);        // top-left red
    EXPECT_EQ(px[4 * 4 * 2], 0);  // bottom-left black
}

TEST(FrameImage, HugeValuesClampInsteadOfBecomingInfinite) {
    const std::string dir = test::scratch_dir("frame_image_clamp");
    Image im;
    im.width = 3;
    im.height = 1;
    im.rgba = {1e6f,  70000.0f, std::numeric_limits<float>::infinity(),  1.0f, -1e6f, 65504.0f,
               1e30f, 1.0f,     std::numeric_limits<float>::quiet_NaN(), 0.5f, 2.0f,  1.0f};
    FrameMetadata meta;
    meta.frame = 7;
    const auto paths = write_frame(dir, im, meta, {"exr", "png"}, 1.0);
    const Image exr = read_image(paths[0]);
    for (float v : exr.rgba) EXPECT_TRUE(std::isfinite(v)) << v;
    EXPECT_FLOAT_EQ(exr.pixel(0, 0)[0], 1e6f);  // HDR values survive (the Sun is ~2e9 cd/m^2)
    EXPECT_FLOAT_EQ(exr.pixel(0, 0)[1], 70000.0f);
    EXPECT_FLOAT_EQ(exr.pixel(0, 0)[2], std::numeric_limits<float>::max());  // +inf clamps
    EXPECT_FLOAT_EQ(exr.pixel(1, 0)[2], 1e30f);
    EXPECT_FLOAT_EQ(exr.pixel(2, 0)[0], 0.0f);  // NaN becomes 0
    EXPECT_FLOAT_EQ(exr.pixel(2, 0)[1], 0.5f);
    const Image png = read_image(paths[1]);
    for (float v : png.rgba) EXPECT_TRUE(std::isfinite(v)) << v;
    EXPECT_FLOAT_EQ(png.pixel(0, 0)[0], 1.0f);
    EXPECT_FLOAT_EQ(png.pixel(1, 0)[0], 1.0f);  // brighter than white: white, the negative red too
    // NaN counts as 0, as in the EXR: (0, 0.5, 2) mapped at its luminance.
    const float* nan_px = png.pixel(2, 0);
    EXPECT_NEAR(0.2126f * nan_px[0] + 0.7152f * nan_px[1] + 0.0722f * nan_px[2], 0.7152f * 0.5f + 0.0722f * 2.0f,
                0.01f);

    // Exposure multiplies the stored value (no half-float ceiling any more).
    Image one;
    one.width = one.height = 1;
    one.rgba = {40000.0f, 1.0f, 0.0f, 1.0f};
    meta.frame = 8;
    const auto p2 = write_frame(dir, one, meta, {"exr"}, 2.0);
    const Image e2 = read_image(p2[0]);
    EXPECT_FLOAT_EQ(e2.rgba[0], 80000.0f);
    EXPECT_FLOAT_EQ(e2.rgba[1], 2.0f);
}

TEST(FrameImage, UnwritablePathThrowsNamingThePath) {
    const std::string dir = test::scratch_dir("frame_image_unwritable");
    const std::string blocker = dir + "/not_a_dir";
    test::write_text(blocker, "a regular file where a folder should be");
    const std::string target = blocker + "/frames";
    Image im;
    im.width = im.height = 2;
    im.rgba.assign(16, 0.5f);
    for (const char* fmt : {"png", "exr"}) {
        try {
            write_frame(target, im, {}, {fmt}, 1.0);
            FAIL() << "write_frame into " << target << " did not throw";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
        }
    }
}

TEST(FrameImage, UnreadableFileThrowsNamingThePath) {
    const std::string dir = test::scratch_dir("frame_image_unreadable");
    const std::string bogus = dir + "/frame_000001.exr";
    test::write_text(bogus, "not an image");
    for (const std::string& path : {bogus, dir + "/missing.png"}) {
        try {
            read_image(path);
            FAIL() << "read_image(" << path << ") did not throw";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
}

TEST(FrameImage, BadInputsThrow) {
    const std::string dir = test::scratch_dir("frame_image_bad");
    Image im;
    im.width = 2;
    im.height = 2;
    im.rgba.assign(3, 0.0f);  // wrong size
    EXPECT_THROW(write_frame(dir, im, {}, {"png"}, 1.0), std::runtime_error);
    im.rgba.assign(16, 0.0f);
    EXPECT_THROW(write_frame(dir, im, {}, {"tiff"}, 1.0), std::runtime_error);
    EXPECT_THROW(write_frame(dir, im, {}, {"png"}, 0.0), std::runtime_error);
}

TEST(FrameImage, LargeFrameNumbersSurvive) {
    const std::string dir = test::scratch_dir("frame_image_bigframe");
    Image im;
    im.width = im.height = 1;
    im.rgba = {0.1f, 0.2f, 0.3f, 1.0f};
    FrameMetadata meta = sample_meta();
    meta.frame = 5000000000ULL;  // beyond a 32-bit int
    const auto paths = write_frame(dir, im, meta, {"exr", "png"}, 1.0);
    for (const auto& p : paths) {
        FrameMetadata back;
        read_image(p, &back);
        EXPECT_EQ(back.frame, meta.frame) << p;
    }
}

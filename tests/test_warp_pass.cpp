// The projector pass (slave/output/warp_pass) on a real headless EGL context, against CPU
// references written here from the contract (common/calibration/projector_warp.hpp): the grid's
// bilinear lookup, GL's bilinear sampling (shading::textureLod) and the shared blend functions
// (shaders/shared/projector_blend.glsl compiled as C++). Small rasters: llvmpipe on 2 cores.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>

#include "calibration/bourke_mesh.hpp"
#include "calibration/mpcdi_package.hpp"
#include "calibration/mpcdi_writer.hpp"
#include "calibration/reference_warp.hpp"
#include "gl/egl_context.hpp"
#include "gl/gl_texture.hpp"
#include "image/frame_image.hpp"
#include "output/warp_pass.hpp"
#include "shading/shared_shading.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {

EglContext& context() { return test::headless_gl(); }

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Content as the CPU samples it (row 0 at v = 0, the bottom) and as a GL texture (nearest
// filtering: the pass must sample it bilinearly through its own sampler anyway).
struct Content {
    sh::Texture2DData data;
    std::unique_ptr<GlTexture> texture;
    template <typename F>
    Content(int w, int h, F value_at_texel) {
        data.width = w;
        data.height = h;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) data.texels.push_back(value_at_texel(x, y));
        texture = std::make_unique<GlTexture>(w, h, data.texels.data(), GL_NEAREST);
    }
    sh::vec4 sample(glm::dvec2 uv) const { return sh::textureLod(sh::sampler2D{&data}, sh::vec2(uv), 0.0); }
};

// A grid of columns x rows in fill layout over a w x h raster, (u, v) = f(raster x, y from the top).
template <typename F>
ProjectorWarp grid_warp(int w, int h, int columns, int rows, F uv_at_pixel) {
    ProjectorWarp warp;
    warp.source = "test grid";
    warp.raster_width = w;
    warp.raster_height = h;
    warp.grid.columns = columns;
    warp.grid.rows = rows;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const glm::dvec2 p = grid_point_pixel(i, j, columns, rows, w, h);
            warp.grid.uv.push_back(uv_at_pixel(p.x, p.y));
        }
    return warp;
}

// The contract's lookup on the CPU: the grid value (u, v, intensity) at raster position (px, py),
// bilinear, the edge value holding beyond the outer points; nullopt where a corner is NaN.
std::optional<glm::dvec3> cpu_lookup(const ProjectorWarp& w, double px, double py) {
    const WarpGrid& g = w.grid;
    const double gx = std::clamp(px * g.columns / w.raster_width - 0.5, 0.0, g.columns - 1.0);
    const double gy = std::clamp(py * g.rows / w.raster_height - 0.5, 0.0, g.rows - 1.0);
    const int i0 = std::min(static_cast<int>(std::floor(gx)), g.columns - 2);
    const int j0 = std::min(static_cast<int>(std::floor(gy)), g.rows - 2);
    const double fx = gx - i0, fy = gy - j0;
    auto at = [&](int i, int j) {
        const size_t k = static_cast<size_t>(j) * g.columns + i;
        return glm::dvec3(g.uv[k], g.intensity.empty() ? 1.0 : g.intensity[k]);
    };
    const glm::dvec3 a = at(i0, j0), b = at(i0 + 1, j0), c = at(i0, j0 + 1), d = at(i0 + 1, j0 + 1);
    for (const auto& p : {a, b, c, d})
        if (std::isnan(p.x) || std::isnan(p.y)) return std::nullopt;
    return glm::mix(glm::mix(a, b, fx), glm::mix(c, d, fx), fy);
}

double rms(const std::vector<double>& e) {
    double s = 0.0;
    for (double x : e) s += x * x;
    return std::sqrt(s / static_cast<double>(e.size()));
}

}  // namespace

TEST(WarpPass, IdentityReproducesTheContent) {
    context();
    const int w = 64, h = 48;
    const Content content(w, h, [](int x, int y) { return sh::vec4(x / 64.0f, y / 48.0f, 0.3f + 0.01f * (x % 7), 1); });
    WarpPass pass(std::nullopt, w, h);
    ASSERT_EQ(pass.width(), w);
    ASSERT_EQ(pass.height(), h);
    pass.draw(content.texture->id(), 1.0);
    const Image lin = pass.read_linear();
    const std::vector<uint8_t> enc = pass.read_encoded();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const sh::vec4 want = content.data.at(x, h - 1 - y);  // raster row 0 is the content's top
            for (int c = 0; c < 3; ++c) {
                ASSERT_NEAR(lin.pixel(x, y)[c], want[c], 1e-5) << x << "," << y << " channel " << c;
                const int code = static_cast<int>(std::lround(linear_to_srgb(want[c]) * 255.0f));
                ASSERT_NEAR(enc[(static_cast<size_t>(y) * w + x) * 4 + c], code, 1) << x << "," << y;
            }
        }
}

TEST(WarpPass, AHalfTurnIsExact) {
    context();
    const int w = 40, h = 30;
    const Content content(w, h, [](int x, int y) { return sh::vec4(x / 40.0f, y / 30.0f, 0.5f, 1); });
    // Raster pixel (x, y from the top) shows content texel (w - 1 - x, y from the bottom).
    WarpPass pass(grid_warp(w, h, w, h, [&](double px, double py) { return glm::dvec2(1.0 - px / w, py / h); }), w, h);
    pass.draw(content.texture->id(), 1.0);
    const Image lin = pass.read_linear();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(lin.pixel(x, y)[c], content.data.at(w - 1 - x, y)[c], 1e-5) << x << "," << y;
}

TEST(WarpPass, CurvedGridMatchesTheBilinearCpuReference) {
    context();
    const int w = 80, h = 60, cw = 64, ch = 64;
    const Content content(cw, ch, [](int x, int y) {
        return sh::vec4(0.5f + 0.4f * std::sin(x * 0.2f), 0.5f + 0.4f * std::cos(y * 0.15f), (x + y) / 128.0f, 1);
    });
    // A barrel-like map (not representable by one bilinear patch) on a coarse 9x7 grid.
    const ProjectorWarp warp = grid_warp(w, h, 9, 7, [&](double px, double py) {
        const double x = px / w * 2.0 - 1.0, y = 1.0 - py / h * 2.0, r2 = x * x + y * y;
        return glm::dvec2(0.5 + 0.45 * x * (1.0 - 0.15 * r2), 0.5 + 0.45 * y * (1.0 - 0.15 * r2));
    });
    WarpPass pass(warp, cw, ch, WarpOptions{WarpOptions::Encode::Gamma, 1});
    pass.draw(content.texture->id(), 1.0);
    const Image lin = pass.read_linear();
    double worst = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto g = cpu_lookup(warp, x + 0.5, y + 0.5);
            ASSERT_TRUE(g.has_value());
            const sh::vec4 want = content.sample(glm::dvec2(*g));
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(lin.pixel(x, y)[c]) - want[c]));
        }
    // GL's bilinear weights have 8 fractional bits: 1/512 of a texel step (<= 0.025 here).
    EXPECT_LT(worst, 2e-3);
}

TEST(WarpPass, NanPointsAndUvOutsideTheContentAreBlack) {
    context();
    const int w = 50, h = 50;
    const Content content(8, 8, [](int, int) { return sh::vec4(0.5f, 0.5f, 0.5f, 1); });
    // u runs from -0.2 to 1.2 across the raster; grid point (2, 2) of 5x5 is unknown.
    ProjectorWarp warp =
        grid_warp(w, h, 5, 5, [&](double px, double py) { return glm::dvec2(-0.2 + 1.4 * px / w, 1.0 - py / h); });
    warp.grid.uv[2 * 5 + 2] = glm::dvec2(kNaN, kNaN);
    warp.beta = BlendMap{1, 1, {0.05f}};  // black content is still lifted to the projector's black
    WarpPass pass(warp, 8, 8);
    pass.draw(content.texture->id(), 1.0);
    const Image lin = pass.read_linear();
    int black = 0, lit = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // Cells touching point (2, 2) span grid coordinates [1, 3): pixel centres 15.5 .. 34.5.
            const bool nan_cell = x >= 15 && x < 35 && y >= 15 && y < 35;
            const double u = -0.2 + 1.4 * (x + 0.5) / w;
            const bool outside = u < 0.0 || u > 1.0;
            const float v = lin.pixel(x, y)[0];
            if (nan_cell || outside) {
                ASSERT_NEAR(v, 0.05f, 1e-6) << x << "," << y;
                ++black;
            } else {
                ASSERT_NEAR(v, 0.5f * 0.95f + 0.05f, 1e-5) << x << "," << y;
                ++lit;
            }
        }
    EXPECT_GT(black, 400);
    EXPECT_GT(lit, 1000);
}

TEST(WarpPass, BlendMapsIntensityAndGammaFollowTheSharedRule) {
    context();
    const int w = 40, h = 30;
    const Content content(w, h, [](int x, int y) { return sh::vec4(x / 40.0f, y / 30.0f, 1.1f, 1); });
    ProjectorWarp warp = grid_warp(w, h, 8, 6, [&](double px, double py) { return glm::dvec2(px / w, 1.0 - py / h); });
    for (int k = 0; k < 48; ++k) warp.grid.intensity.push_back(0.2f + 0.8f * float((k * 7) % 48) / 47.0f);
    warp.alpha = BlendMap{5, 4, {}};
    for (int k = 0; k < 20; ++k) warp.alpha.value.push_back(0.3f + 0.035f * k);
    warp.beta = BlendMap{3, 3, {0.0f, 0.02f, 0.04f, 0.06f, 0.08f, 0.1f, 0.12f, 0.14f, 0.16f}};
    warp.projector_gamma = 2.4;
    const double exposure = 0.8;
    WarpPass pass(warp, w, h, WarpOptions{WarpOptions::Encode::Gamma, 4});
    pass.draw(content.texture->id(), exposure);
    const Image lin = pass.read_linear();
    const std::vector<uint8_t> enc = pass.read_encoded();
    auto map_texture = [](const BlendMap& m) {
        sh::Texture2DData t{m.width, m.height, {}};  // row 0 is the raster's top, sampled at y / h
        for (float v : m.value) t.texels.push_back(sh::vec4(v));
        return t;
    };
    const sh::Texture2DData alpha = map_texture(warp.alpha), beta = map_texture(warp.beta);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const sh::vec2 t((x + 0.5f) / w, (y + 0.5f) / h);
            const glm::dvec3 g = *cpu_lookup(warp, x + 0.5, y + 0.5);
            const sh::vec3 c = sh::vec3(content.sample(glm::dvec2(g))) * static_cast<float>(exposure);
            const sh::vec3 want = sh::projector_blend(c, sh::textureLod(sh::sampler2D{&alpha}, t, 0.0).r,
                                                      static_cast<float>(g.z), sh::textureLod({&beta}, t, 0.0).r);
            const sh::vec3 code = sh::projector_encode(want, 2.4f, sh::PROJECTOR_ENCODE_GAMMA) * 255.0f;
            for (int k = 0; k < 3; ++k) {
                ASSERT_NEAR(lin.pixel(x, y)[k], want[k], 2e-3) << x << "," << y << " channel " << k;
                ASSERT_NEAR(enc[(static_cast<size_t>(y) * w + x) * 4 + k], code[k], 1.01) << x << "," << y;
            }
        }
}

// A checker of one-texel squares seen through a rotated, minifying warp (3.3 texels per projector
// pixel): one bilinear tap per pixel aliases; the footprint filter comes close to the area mean.
TEST(WarpPass, FootprintFilterApproachesTheAreaAverage) {
    context();
    const int w = 96, h = 96, n = 512;
    const Content content(n, n, [](int x, int y) { return sh::vec4(float((x + y) % 2)); });
    const double s = 3.3 * w / n, a = 20.0 * std::numbers::pi / 180.0;
    auto uv_at = [&](double px, double py) {  // raster -> content, centred, rotated by a
        const double x = (px - w / 2.0) / w * s, y = (h / 2.0 - py) / h * s;
        return glm::dvec2(0.5 + std::cos(a) * x - std::sin(a) * y, 0.5 + std::sin(a) * x + std::cos(a) * y);
    };
    const ProjectorWarp warp = grid_warp(w, h, w, h, uv_at);
    std::vector<double> err_one_tap, err_filtered;
    for (int taps : {1, 4}) {
        WarpPass pass(warp, n, n, WarpOptions{WarpOptions::Encode::Gamma, taps});
        pass.draw(content.texture->id(), 1.0);
        const Image lin = pass.read_linear();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double mean = 0.0;  // the area average over the pixel: 16 x 16 point samples
                for (int j = 0; j < 16; ++j)
                    for (int i = 0; i < 16; ++i) {
                        const glm::dvec2 uv = uv_at(x + (i + 0.5) / 16.0, y + (j + 0.5) / 16.0);
                        mean += ((int(std::floor(uv.x * n)) + int(std::floor(uv.y * n))) % 2) / 256.0;
                    }
                (taps == 1 ? err_one_tap : err_filtered).push_back(lin.pixel(x, y)[0] - mean);
            }
    }
    const double one = rms(err_one_tap), filtered = rms(err_filtered);
    std::printf("checker 3.3 texels per pixel: rms error one tap %.4f, footprint filter %.4f\n", one, filtered);
    EXPECT_GT(one, 0.1);  // the aliasing is there to remove
    EXPECT_LT(filtered, 0.35 * one);
}

TEST(WarpPass, MalformedWarpIsNamedInTheError) {
    context();
    ProjectorWarp warp = grid_warp(16, 16, 3, 3, [](double, double) { return glm::dvec2(0.5); });
    warp.source = "dome.mpcdi region proj2";
    warp.grid.uv.pop_back();
    try {
        WarpPass pass(warp, 16, 16);
        FAIL() << "a short grid was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("dome.mpcdi region proj2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("warp grid"), std::string::npos) << e.what();
    }
    warp = grid_warp(16, 16, 1, 3, [](double, double) { return glm::dvec2(0.5); });
    EXPECT_THROW(WarpPass(warp, 16, 16), std::invalid_argument);
}

// ---- cupola-warp on files written here, against the CPU reference warp -------------------------

namespace {

// A smooth frame in [0, 0.9] (no clipping, so the reference's unclipped blend applies), written as
// an EXR; returned as the reference's LinearImage (row 0 the top).
LinearImage write_test_frame(const std::string& dir, int w, int h, std::string* path) {
    Image img{w, h, std::vector<float>(static_cast<size_t>(w) * h * 4)};
    LinearImage lin{w, h, 3, std::vector<float>(static_cast<size_t>(w) * h * 3)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c) {
                const float v = c == 3 ? 1.0f : 0.45f + 0.45f * std::sin(0.15f * x * (c + 1) + 0.1f * y);
                img.pixel(x, y)[c] = v;
                if (c < 3) lin.data[(static_cast<size_t>(y) * w + x) * 3 + c] = v;
            }
    *path = write_frame(dir, img, FrameMetadata{}, {"exr"}, 1.0).front();
    return lin;
}

// A curved 9x7 warp over a 40x30 raster with alpha and beta maps: one region of a 2d package.
ProjectorWarp test_region_warp() {
    const int w = 40, h = 30;
    ProjectorWarp warp = grid_warp(w, h, 9, 7, [&](double px, double py) {
        const double x = px / w * 2.0 - 1.0, y = 1.0 - py / h * 2.0, r2 = x * x + y * y;
        return glm::dvec2(0.5 + 0.4 * x * (1.0 - 0.2 * r2) + 0.03 * y, 0.5 + 0.4 * y * (1.0 - 0.1 * r2));
    });
    warp.grid.uv[3] = glm::dvec2(kNaN, kNaN);  // an unknown point
    warp.alpha = BlendMap{10, 8, {}};
    for (int k = 0; k < 80; ++k) warp.alpha.value.push_back(0.25f + 0.75f * float(k % 10) / 9.0f);
    warp.beta = BlendMap{4, 4, std::vector<float>(16, 0.03f)};
    warp.region_id = "proj1";
    return warp;
}

std::string write_package(const std::string& file, const ProjectorWarp& warp, const MpcdiWriting& writing) {
    MpcdiPackageOut package;
    package.profile = "2d";
    package.geometry_level = 2;
    package.color_level = 2;
    MpcdiRegionOut region;
    region.id = warp.region_id;
    region.warp = warp;
    package.regions = {region};
    write_mpcdi(file, package, writing);
    return file;
}

std::pair<int, std::string> cupola_warp(const std::string& args) {
    return test::run_shell(test::bin_path("cupola-warp") + " " + args + " 2>&1");
}

// Largest difference of the RGB channels of an RGBA image file against a reference (the shown
// pixels and the black ones alike).
double worst_difference(const Image& got, const LinearImage& want) {
    EXPECT_EQ(got.width, want.width);
    EXPECT_EQ(got.height, want.height);
    if (got.width != want.width || got.height != want.height) return 1e9;
    double worst = 0.0;
    for (int y = 0; y < got.height; ++y)
        for (int x = 0; x < got.width; ++x)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(double(got.pixel(x, y)[c]) -
                                                 want.data[(static_cast<size_t>(y) * want.width + x) * 3 + c]));
    return worst;
}

}  // namespace

TEST(WarpTool, MpcdiRegionMatchesTheReferenceWarpInExrAndPng) {
    const std::string dir = test::scratch_dir("WarpTool_mpcdi");
    std::string frame;
    const LinearImage content = write_test_frame(dir, 64, 48, &frame);
    MpcdiWriting writing;
    writing.gamma_embedded = 2.2;
    const std::string package = write_package(dir + "/dome.mpcdi", test_region_warp(), writing);
    const auto [rc, out] =
        cupola_warp("--mpcdi " + package + " --region proj1 --filter 1 --in " + frame + " --out " + dir + "/proj1.exr");
    ASSERT_EQ(rc, 0) << out;
    // The reference reads the same package (alpha as quantized in its PNG) with the same rules.
    const ProjectorWarp read_back = MpcdiPackage::open(package).read_region("proj1");
    const LinearImage want = reference_warp(read_back, content);
    EXPECT_LT(worst_difference(read_image(dir + "/proj1.exr"), want), 3e-3);

    const auto [rc2, out2] = cupola_warp("--mpcdi " + package + " --filter 1 --in " + frame + " --out " + dir +
                                         "/proj1.png");  // the only region: no --region needed
    ASSERT_EQ(rc2, 0) << out2;
    FrameMetadata meta;
    const Image png = read_image(dir + "/proj1.png", &meta);  // decoded as sRGB: undo it to the codes
    ASSERT_EQ(png.width, 40);
    int off = 0;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x) {
            const float lin = want.data[(static_cast<size_t>(y) * 40 + x) * 3];
            const double code = std::pow(std::clamp(lin, 0.0f, 1.0f), 1.0 / read_back.projector_gamma) * 255.0;
            const double got = linear_to_srgb(png.pixel(x, y)[0]) * 255.0;
            off += std::abs(got - code) > 1.01;
        }
    EXPECT_EQ(off, 0) << "pixels whose code differs by more than 1 from pow(reference, 1/gamma)";
}

TEST(WarpTool, EveryReadingSwitchGivesTheSameProjectorImage) {
    const std::string dir = test::scratch_dir("WarpTool_switches");
    std::string frame;
    write_test_frame(dir, 64, 48, &frame);
    const ProjectorWarp warp = test_region_warp();
    std::vector<float> first;
    struct Variant {
        std::string name, flags;
        MpcdiReading layout;
        PfmByteOrder order;
    };
    std::vector<Variant> variants = {{"default", "", {}, PfmByteOrder::little_endian}};
    variants.push_back({"top-first", "--pfm-rows top-first", {}, PfmByteOrder::big_endian});
    variants.back().layout.pfm_rows = PfmRows::top_first;
    variants.push_back({"v-top", "--v-origin top", {}, PfmByteOrder::little_endian});
    variants.back().layout.v_origin = VOrigin::top;
    variants.push_back({"buffer", "--coordinates buffer", {}, PfmByteOrder::little_endian});
    variants.back().layout.coordinates = WarpCoordinates::buffer;
    for (const Variant& v : variants) {
        MpcdiWriting writing;
        writing.layout = v.layout;
        writing.pfm_byte_order = v.order;
        const std::string package = write_package(dir + "/" + v.name + ".mpcdi", warp, writing);
        const std::string out_file = dir + "/" + v.name + ".exr";
        const auto [rc, out] =
            cupola_warp("--mpcdi " + package + " " + v.flags + " --in " + frame + " --out " + out_file);
        ASSERT_EQ(rc, 0) << v.name << ": " << out;
        const Image img = read_image(out_file);
        if (first.empty()) {
            first = img.rgba;
            continue;
        }
        ASSERT_EQ(img.rgba.size(), first.size()) << v.name;
        double worst = 0.0;
        for (size_t i = 0; i < first.size(); ++i) worst = std::max(worst, double(std::abs(img.rgba[i] - first[i])));
        EXPECT_LT(worst, 1e-4) << v.name;
    }
}

TEST(WarpTool, BourkeMeshMatchesTheReferenceWarp) {
    const std::string dir = test::scratch_dir("WarpTool_bourke");
    std::string frame;
    const LinearImage content = write_test_frame(dir, 64, 64, &frame);
    // A 9x7 node mesh over a 4:3 screen (x in [-4/3, 4/3], y in [-1, 1] up), a mild barrel map,
    // the intensity falling toward the right edge.
    std::string text = "2\n9 7\n";
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 9; ++i) {
            const double x = (i / 8.0 * 2.0 - 1.0) * 4.0 / 3.0, y = j / 6.0 * 2.0 - 1.0;
            const double r2 = x * x * 0.5 + y * y;
            char line[128];
            std::snprintf(line, sizeof line, "%.6f %.6f %.6f %.6f %.4f\n", x, y, 0.5 + 0.3 * x * (1 - 0.1 * r2),
                          0.5 + 0.4 * y * (1 - 0.1 * r2), 1.0 - 0.4 * i / 8.0);
            text += line;
        }
    test::write_text(dir + "/mirror.data", text);
    const auto [rc, out] = cupola_warp("--bourke " + dir + "/mirror.data --raster 48x36 --filter 1 --in " + frame +
                                       " --out " + dir + "/mirror.exr");
    ASSERT_EQ(rc, 0) << out;
    const LinearImage want = reference_warp(read_bourke_mesh(dir + "/mirror.data", 48, 36), content);
    EXPECT_LT(worst_difference(read_image(dir + "/mirror.exr"), want), 3e-3);
}

TEST(WarpTool, BadInputsAreNamedAndRefused) {
    const std::string dir = test::scratch_dir("WarpTool_bad");
    std::string frame;
    write_test_frame(dir, 16, 16, &frame);
    test::write_text(dir + "/broken.mpcdi", "this is not a zip");
    auto [rc, out] = cupola_warp("--mpcdi " + dir + "/broken.mpcdi --in " + frame + " --out " + dir + "/o.png");
    EXPECT_NE(rc, 0);
    EXPECT_NE(out.find("broken.mpcdi"), std::string::npos) << out;
    test::write_text(dir + "/bad.data", "2\n3 3\n0 0 0.5 0.5 1\n");
    std::tie(rc, out) =
        cupola_warp("--bourke " + dir + "/bad.data --raster 16x16 --in " + frame + " --out " + dir + "/o.png");
    EXPECT_NE(rc, 0);
    EXPECT_NE(out.find("bad.data"), std::string::npos) << out;
    std::tie(rc, out) =
        cupola_warp("--bourke " + dir + "/bad.data --raster 16by16 --in " + frame + " --out " + dir + "/o.png");
    EXPECT_EQ(rc, 2);
    EXPECT_NE(out.find("--raster"), std::string::npos) << out;
    std::tie(rc, out) = cupola_warp("--bourke " + dir + "/bad.data --raster 16x16 --in " + frame + " --out o.tif");
    EXPECT_EQ(rc, 2);
    EXPECT_NE(out.find("--out"), std::string::npos) << out;
}

// Against an independent reading: tools/mpcdi_reference.py reads a package after PyMPCDI's
// conventions (numpy, its own PFM, XML and PNG decoding: first PFM row the top, region-local
// (u, v), alpha = stored^gammaEmbedded, the CPU blend). cupola-warp with the switch that matches
// PyMPCDI (--pfm-rows top-first) must give the same projector image on the GPU, for a region that
// sits inside its buffer (so region-local and buffer-global coordinates differ); the default
// reading of the same file must not.
TEST(WarpTool, AgreesWithThePyMpcdiReading) {
    // The Python with Debian's python3-numpy and python3-openimageio (scripts/setup.sh): the first
    // python3 on PATH may be another installation.
    std::string interpreter;
    for (const std::string candidate : {"python3", "/usr/bin/python3"})
        if (interpreter.empty() && test::run_shell(candidate + " -c 'import numpy, OpenImageIO' 2>&1").first == 0)
            interpreter = candidate;
    ASSERT_FALSE(interpreter.empty()) << "no python3 with numpy and OpenImageIO (scripts/setup.sh installs them)";
    const std::string dir = test::scratch_dir("WarpTool_pympcdi");
    std::string frame;
    write_test_frame(dir, 64, 48, &frame);
    MpcdiPackageOut package;
    package.profile = "2d";
    package.geometry_level = 2;
    package.color_level = 2;
    MpcdiRegionOut region{"proj1", 0.25, 0.1, 0.5, 0.6, test_region_warp()};
    package.regions = {region};
    MpcdiWriting writing;
    writing.layout.pfm_rows = PfmRows::top_first;
    writing.gamma_embedded = 2.2;
    writing.map_bit_depth = 16;
    write_mpcdi(dir + "/p.mpcdi", package, writing);
    const auto [rc, out] =
        test::run_shell(interpreter + " " + test::source_path("tools/mpcdi_reference.py") + " --mpcdi " + dir +
                        "/p.mpcdi --region proj1 --in " + frame + " --out " + dir + "/python.exr 2>&1");
    ASSERT_EQ(rc, 0) << out;
    const Image python = read_image(dir + "/python.exr");
    auto difference = [&](const std::string& flags, const std::string& name) {
        const auto [rc2, out2] = cupola_warp("--mpcdi " + dir + "/p.mpcdi --region proj1 --filter 1 " + flags +
                                             " --in " + frame + " --out " + dir + "/" + name);
        EXPECT_EQ(rc2, 0) << out2;
        const Image gpu = read_image(dir + "/" + name);
        EXPECT_EQ(gpu.width, python.width);
        EXPECT_EQ(gpu.height, python.height);
        double worst = gpu.width == python.width && gpu.height == python.height ? 0.0 : 1e9;
        for (size_t i = 0; worst < 1e9 && i < gpu.rgba.size(); ++i)
            if (i % 4 != 3) worst = std::max(worst, double(std::abs(gpu.rgba[i] - python.rgba[i])));
        return worst;
    };
    EXPECT_LT(difference("--pfm-rows top-first", "matched.exr"), 3e-3);
    EXPECT_GT(difference("", "default.exr"), 0.05);
}

// The eye's loss of acuity at night (shaders/shared/night_acuity.glsl, common/dome/acuity_blur,
// shaders/warp.frag): the blur's width follows Ferwerda et al.'s (1996) fit of Shlaer's (1937)
// acuity, its 13 taps are a Gaussian of that width, a point spreads by the same angle on a channel
// and on the domemaster whatever their pixel sizes, the warp pass on a real EGL context blurs as
// the CPU does, and the stitched domemaster's PNG is blurred while its EXR is not.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/type_ptr.hpp>
#include <numbers>

#include "config/cluster_config.hpp"
#include "dome/acuity_blur.hpp"
#include "dome/domemaster_stitcher.hpp"
#include "gl/gl_texture.hpp"
#include "image/frame_image.hpp"
#include "output/warp_pass.hpp"
#include "shading/shared_shading.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;
namespace sh = cupola::shading;
namespace fs = std::filesystem;

namespace {

// Shlaer's acuity as Ferwerda et al. fitted it, in double, written from the paper's equation.
double ferwerda_cycles_per_deg(double l_cd_m2) { return 17.25 * std::atan(1.4 * std::log10(l_cd_m2) + 0.35) + 25.72; }

Image black_image(int w, int h) {
    Image im;
    im.width = w;
    im.height = h;
    im.rgba.assign(static_cast<size_t>(w) * h * 4, 0.0f);
    for (size_t i = 3; i < im.rgba.size(); i += 4) im.rgba[i] = 1.0f;
    return im;
}

// A point of light: one pixel, the one that looks along dir, set to `value`.
glm::ivec2 put_point(Image& im, const PixelRays& rays, const glm::dvec3& dir, float value) {
    const glm::dvec2 p = *rays.pixel(dir);
    const glm::ivec2 at(static_cast<int>(p.x), static_cast<int>(p.y));
    for (int c = 0; c < 3; ++c) im.pixel(at.x, at.y)[c] = value;
    return at;
}

// The spread of the light about `centre`: sqrt(E[angle^2] / 2) in degrees, the standard deviation
// per axis of an isotropic 2-D spot, the light weighted by the pixels' red.
double spread_deg(const Image& im, const PixelRays& rays, const glm::dvec3& centre) {
    double sum = 0.0, sum_a2 = 0.0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            const double v = im.pixel(x, y)[0];
            const auto d = rays.direction({x + 0.5, y + 0.5});
            if (v <= 0.0 || !d) continue;
            const double a = std::acos(std::clamp(glm::dot(*d, centre), -1.0, 1.0));
            sum += v;
            sum_a2 += v * a * a;
        }
    return glm::degrees(std::sqrt(sum_a2 / sum / 2.0));
}

ChannelFrustum narrow_channel(int size) {
    return ChannelFrustum(EulerDeg{20, 35, 0}, FovDeg{10, 10, 10, 10}, size, size);
}

}  // namespace

TEST(NightAcuity, TheBlurFollowsFerwerdasFitAndHalvesTheFinestGratingsContrast) {
    float previous = 0.0f;
    for (double l : {1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0}) {
        const float r = sh::acuity_cycles_per_deg(static_cast<float>(l));
        EXPECT_NEAR(r, ferwerda_cycles_per_deg(l), 1e-3 * ferwerda_cycles_per_deg(l)) << l;
        EXPECT_GT(r, previous) << l;  // the eye resolves more as the light grows
        previous = r;
        // The Gaussian's transfer function at that grating, exp(-2 pi^2 sigma^2 f^2), is one half.
        const double sigma_rad = sh::acuity_blur_sigma_rad(static_cast<float>(l));
        const double f_per_rad = ferwerda_cycles_per_deg(l) * 180.0 / std::numbers::pi;
        const double pi2 = std::numbers::pi * std::numbers::pi;
        EXPECT_NEAR(std::exp(-2.0 * pi2 * sigma_rad * sigma_rad * f_per_rad * f_per_rad), 0.5, 1e-3) << l;
    }
    EXPECT_NEAR(glm::degrees(sh::acuity_blur_sigma_rad(1e-3f)), 0.063, 0.001);  // the header's figures
    EXPECT_NEAR(glm::degrees(sh::acuity_blur_sigma_rad(0.1f)), 0.016, 0.001);
    EXPECT_EQ(sh::acuity_blur_sigma_rad(0.0f), 0.0f);  // night vision off
}

TEST(NightAcuity, TheThirteenTapsAreAGaussianOfThatWidth) {
    double w = 0, mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
    for (int k = 0; k < sh::ACUITY_TAPS; ++k) {
        const glm::vec3 t = sh::acuity_tap(k);
        w += t.z;
        mx += t.z * t.x;
        my += t.z * t.y;
        xx += t.z * t.x * t.x;
        yy += t.z * t.y * t.y;
        xy += t.z * t.x * t.y;
    }
    EXPECT_NEAR(w, 1.0, 1e-6);
    EXPECT_NEAR(mx, 0.0, 1e-6);
    EXPECT_NEAR(my, 0.0, 1e-6);
    EXPECT_NEAR(xx, 1.0, 1e-5);  // sigma^2 along each axis, none across
    EXPECT_NEAR(yy, 1.0, 1e-5);
    EXPECT_NEAR(xy, 0.0, 1e-6);
    // The taps are arcs on the sky of their offset's length, wherever the pixel looks.
    const float sigma_rad = 0.01f;
    for (const glm::vec3 d : {glm::vec3(0, 0, -1), glm::normalize(glm::vec3(0.99f, 0.1f, 0.05f)), glm::vec3(0, 1, 0)})
        for (int k = 0; k < sh::ACUITY_TAPS; ++k) {
            const glm::vec3 t = sh::acuity_tap(k);
            const glm::vec3 dk = sh::acuity_tap_direction(d, sigma_rad, k);
            EXPECT_NEAR(glm::length(dk), 1.0f, 1e-6f);
            const double angle = std::acos(std::clamp(static_cast<double>(glm::dot(d, dk)), -1.0, 1.0));
            EXPECT_NEAR(angle, std::hypot(t.x, t.y) * sigma_rad, 3e-4 * sigma_rad + 2e-4) << k;
        }
}

// The blur is taken in angle: a point spreads by sigma degrees on a channel of 20 px a degree and
// on a domemaster of 5.7 px a degree alike, so two images of one sky blur it the same.
TEST(AcuityBlur, APointSpreadsByTheSameAngleOnAChannelAndOnTheDomemaster) {
    const double sigma_deg = 0.25;
    const ChannelFrustum frustum = narrow_channel(400);
    const ChannelRays channel(frustum);
    const DomemasterRays dome(180.0, 1024);
    const glm::dvec3 dir = frustum.pixel_to_dome_direction({200.0, 200.0});
    for (const PixelRays* rays : {static_cast<const PixelRays*>(&channel), static_cast<const PixelRays*>(&dome)}) {
        const int size = rays == &channel ? 400 : 1024;
        Image im = black_image(size, size);
        const glm::ivec2 at = put_point(im, *rays, dir, 100.0f);
        const glm::dvec3 centre = *rays->direction({at.x + 0.5, at.y + 0.5});
        const Image blurred = acuity_blurred(im, *rays, glm::radians(sigma_deg));
        EXPECT_NEAR(spread_deg(blurred, *rays, centre), sigma_deg, 0.04 * sigma_deg) << size;
        // The peak is spread out: on the channel (5 px, 12 passes) as a Gaussian's, whose pixel
        // keeps 1 / (2 pi 25) = 0.6 %; on the domemaster (1.4 px, one pass) the centre tap keeps
        // its 27 %.
        EXPECT_LT(blurred.pixel(at.x, at.y)[0], (size == 400 ? 0.012f : 0.32f) * 100.0f);
    }
}

TEST(AcuityBlur, NoBlurLeavesTheImageAsItIsAndABrightEyeNeedsNone) {
    const ChannelFrustum frustum = narrow_channel(64);
    Image im = black_image(64, 64);
    put_point(im, ChannelRays(frustum), frustum.pixel_to_dome_direction({20.5, 40.5}), 7.0f);
    EXPECT_EQ(acuity_blurred(im, ChannelRays(frustum), 0.0).rgba, im.rgba);  // bit for bit
    const double dome_2k_rad_per_px = glm::radians(180.0) / 2048;
    EXPECT_FALSE(acuity_blur_needed(sh::acuity_blur_sigma_rad(100.0f), dome_2k_rad_per_px));
    EXPECT_FALSE(acuity_blur_needed(sh::acuity_blur_sigma_rad(1.0f), dome_2k_rad_per_px));
    EXPECT_TRUE(acuity_blur_needed(sh::acuity_blur_sigma_rad(1e-3f), dome_2k_rad_per_px));
    EXPECT_TRUE(acuity_blur_needed(sh::acuity_blur_sigma_rad(1e-3f), glm::radians(180.0) / 8192));
}

// On the GPU: the warp pass (identity, the channel's frustum given) blurs the content as
// acuity_blurred does on the CPU.
TEST(AcuityBlur, TheWarpPassBlursAsTheCpuDoes) {
    test::headless_gl();
    const int size = 96;
    const ChannelFrustum frustum = narrow_channel(size);
    const ChannelRays rays(frustum);
    Image im = black_image(size, size);
    // Within the display's range: the pass's linear output is after the gamut map.
    put_point(im, rays, frustum.pixel_to_dome_direction({40.5, 50.5}), 0.9f);
    put_point(im, rays, frustum.pixel_to_dome_direction({70.5, 20.5}), 0.4f);
    std::vector<glm::vec4> texels;  // GL row 0 at the bottom
    for (int y = size - 1; y >= 0; --y)
        for (int x = 0; x < size; ++x) texels.emplace_back(glm::make_vec4(im.pixel(x, y)));
    const GlTexture texture(size, size, texels.data(), GL_NEAREST);
    WarpOptions options;
    options.content_view = frustum;
    WarpPass pass(std::nullopt, size, size, options);
    const double sigma_rad = glm::radians(0.06);  // 0.58 px
    pass.draw(texture.id(), 1.0, 0.0, 0.0, sigma_rad);
    const Image gpu = pass.read_linear();
    const Image cpu = acuity_blurred(im, rays, sigma_rad);
    double worst = 0.0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            worst = std::max(worst, static_cast<double>(std::abs(gpu.pixel(x, y)[0] - cpu.pixel(x, y)[0])));
    EXPECT_LT(worst, 1e-3 * 0.9);
    EXPECT_LT(cpu.pixel(40, 50)[0], 0.8f * 0.9f);  // and it did blur
}

// The stitched domemaster: its PNG shows the eye's blur, its EXR keeps the physical sky.
TEST(AcuityBlur, TheDomemastersPngIsBlurredItsExrIsNot) {
    const std::string root = test::scratch_dir("acuity_blur_stitch");
    ClusterConfig cfg;
    cfg.file = root + "/cluster.json";
    cfg.directory = root;
    cfg.output.formats = {"png", "exr"};
    cfg.output.domemaster_size = 720;  // 0.25 degrees a pixel
    ChannelConfig ch;
    ch.name = "A";
    ch.orientation = EulerDeg{0, 60, 0};
    ch.fov = FovDeg{30, 30, 30, 30};
    ch.width = ch.height = 200;
    cfg.channels = {ch};
    const ChannelFrustum frustum = ch.frustum();
    Image im = black_image(ch.width, ch.height);
    for (int i = 0; i < 5; ++i)  // faint stars on a faint sky, as the eye sees at 1e-6 cd/m^2
        put_point(im, ChannelRays(frustum), frustum.pixel_to_dome_direction({40.5 + 30 * i, 100.5}), 0.5f);
    FrameMetadata meta;
    meta.channel_id = 0;
    meta.channel_name = "A";
    meta.frame = 1;
    meta.snapshot_hash = "00000000000000a1";
    meta.adapted_cd_m2 = 1e-6;
    meta.night_vision = true;
    for (bool blur : {false, true}) {
        meta.acuity_blur = blur;
        const std::string in = root + (blur ? "/blur" : "/sharp");
        write_frame(in + "/A", im, meta, {"exr"}, 1.0);
        const StitchReport r = stitch_run_directory(cfg, in, in + "/dome", std::nullopt, 0);
        ASSERT_EQ(r.frames.size(), 1u);
    }
    FrameMetadata back;
    const Image png_sharp = read_image(root + "/sharp/dome/" + frame_file_name(1, "png"));
    const Image png_blur = read_image(root + "/blur/dome/" + frame_file_name(1, "png"), &back);
    EXPECT_TRUE(back.acuity_blur);
    EXPECT_GT(glm::degrees(back.acuity_sigma_rad()), 0.2);  // a pixel's width at 1e-6 cd/m^2
    EXPECT_EQ(read_image(root + "/sharp/dome/" + frame_file_name(1, "exr")).rgba,
              read_image(root + "/blur/dome/" + frame_file_name(1, "exr")).rgba);
    float peak_sharp = 0.0f, peak_blur = 0.0f;
    for (size_t i = 0; i < png_sharp.rgba.size(); i += 4) {
        peak_sharp = std::max(peak_sharp, png_sharp.rgba[i]);
        peak_blur = std::max(peak_blur, png_blur.rgba[i]);
    }
    EXPECT_LT(peak_blur, 0.8f * peak_sharp);
}

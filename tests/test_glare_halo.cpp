// The glare split (slave/passes/glare_halo_pass.hpp): its wide halo at reduced resolution, its
// core and rays at full resolution, against the whole PSF evaluated per pixel at full resolution
// (glare.halo_downsample 1), rendered by the slave's SceneRenderer through EGL.
//   - Error: on a view with the Sun in the channel and one with the Sun just outside it, the
//     added radiance's relative error (max and 99th percentile over the pixels where the glare
//     is displayable) and its energy.
//   - Seam: a region rendered as one wide channel and as two narrow ones that share its image
//     plane gives the same glare pixel for pixel, within float noise, also with the Sun's core
//     on the seam.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "glare/glare_sources.hpp"
#include "passes/glare_halo_grid.hpp"
#include "scene_renderer.hpp"
#include "show_script.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

EglContext& context() { return test::headless_gl(); }

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// The earth-moon scene without atmospheres (no tables: quick frames), glare on.
SceneConfig space_scene(int downsample) {
    SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    for (auto& b : scene.bodies) {
        b.atmosphere.present = false;
        if (b.kind != BodyKind::Star) b.texture = "generated:" + b.name;
    }
    scene.glare.enabled = true;
    scene.glare.halo_downsample = downsample;
    return scene;
}

// Looking at the Sun from near the Earth, with the shared (analytic) glare sources.
Snapshot sun_snapshot(const SceneConfig& scene) {
    ShowKeyframe k;
    k.sim_time_s = 765806400.0;  // 2024-04-08 12:00 TT
    k.camera.anchor = scene.find("earth")->id;
    k.camera.look_at = scene.find("sun")->id;
    k.camera.offset_m = glm::dvec3(9.2e6, -1.77e7, 4.6e5);
    Snapshot snap = ShowScript({k}, 1.0).evaluate(0.0, scene);
    snap.settings.exposure = 0.5f;
    snap.glare = GlareSources(scene, nullptr).select(snap);
    return snap;
}

ChannelConfig channel(const std::string& name, EulerDeg orientation, FovDeg fov, int w, int h) {
    ChannelConfig ch;
    ch.name = name;
    ch.orientation = orientation;
    ch.fov = fov;
    ch.width = w;
    ch.height = h;
    return ch;
}

// The glare a channel adds: its frame with the glare minus its frame without (everything else
// is drawn the same).
Image glare_image(const std::vector<ChannelConfig>& all, const ChannelConfig& ch, int downsample) {
    context();
    ClusterConfig cluster;
    cluster.channels = all;
    const SceneConfig with = space_scene(downsample);
    SceneConfig without = with;
    without.glare.enabled = false;
    const Snapshot snap = sun_snapshot(with);
    Image on = SceneRenderer(cluster, ch, with).render(snap);
    const Image off = SceneRenderer(cluster, ch, without).render(snap);
    for (size_t i = 0; i < on.rgba.size(); ++i) on.rgba[i] -= off.rgba[i];
    return on;
}

struct GlareError {
    double max = 0.0, p99 = 0.0;  // relative, where the glare is displayable
    double energy_ratio = 0.0;    // split / full, luminance summed over those pixels
    double max_display = 0.0;     // the largest difference anywhere, in display units
    size_t pixels = 0;
};

// The luminance error of `split` against `full`: relative where the full glare is displayable
// (at least glare.min_display after the exposure: fainter glare is not drawn at all), and in
// display units (radiance x exposure; 1 is white) everywhere. Most of the relative error lies in
// the glare's fade to zero at its extent (the last 15 % of its angle), where the halo is faint.
GlareError compare(const Image& split, const Image& full, double exposure) {
    const double floor = SceneConfig().glare.min_display / exposure;
    std::vector<double> rel;
    GlareError e;
    double es = 0.0, ef = 0.0;
    for (int y = 0; y < full.height; ++y)
        for (int x = 0; x < full.width; ++x) {
            const double f = luminance(full.pixel(x, y)), s = luminance(split.pixel(x, y));
            e.max_display = std::max(e.max_display, std::abs(s - f) * exposure);
            if (!(f >= floor)) continue;
            rel.push_back(std::abs(s - f) / f);
            es += s, ef += f;
        }
    e.pixels = rel.size();
    if (rel.empty()) return e;
    std::sort(rel.begin(), rel.end());
    e.max = rel.back();
    e.p99 = rel[std::min(rel.size() - 1, static_cast<size_t>(0.99 * rel.size()))];
    e.energy_ratio = es / ef;
    return e;
}

}  // namespace

TEST(GlareHalo, GridPlacesTheSameTexelsInAWideChannelAndItsHalves) {
    const ChannelFrustum wide(EulerDeg{}, FovDeg{40, 40, 30, 30}, 160, 120);
    const ChannelFrustum left(EulerDeg{}, FovDeg{40, 0, 30, 30}, 80, 120);
    const ChannelFrustum right(EulerDeg{}, FovDeg{0, 40, 30, 30}, 80, 120);
    for (int d : {2, 4, 8}) {
        const GlareHaloGrid w = GlareHaloGrid::for_channel(wide, d), l = GlareHaloGrid::for_channel(left, d),
                            r = GlareHaloGrid::for_channel(right, d);
        // Texel j of one grid is texel j of the other: the same index from the axis and the same
        // tangent at its edge.
        EXPECT_EQ(w.first_x, l.first_x) << d;
        EXPECT_EQ(w.first_y, r.first_y) << d;
        EXPECT_NEAR(-w.tangents.x, -l.tangents.x, 1e-6) << d;
        EXPECT_NEAR(r.tangents.x, -r.first_x * d * std::tan(glm::radians(40.0)) / 80.0, 1e-6) << d;
        // The guard band: every pixel centre's texel coordinate leaves a texel on either side.
        for (const GlareHaloGrid* g : {&w, &l, &r}) {
            const int px = g == &w ? 160 : 80;
            EXPECT_GE(0.5 * g->map.x + g->map.z, 1.5 / g->width) << d;
            EXPECT_LE((px - 0.5) * g->map.x + g->map.z, 1.0 - 1.5 / g->width) << d;
            EXPECT_EQ(g->first_x % 2, 0) << d;
        }
    }
    EXPECT_THROW(GlareHaloGrid::for_channel(wide, 3), std::invalid_argument);
}

TEST(GlareHalo, ReducedResolutionHaloMatchesTheFullResolutionGlare) {
    // The Sun 12 degrees off the axis of a 90-degree channel, then 8 degrees outside its left edge.
    for (double yaw : {12.0, 53.0}) {
        const ChannelConfig ch = channel("front", EulerDeg{yaw, 5.0, 0.0}, FovDeg{45, 45, 45, 45}, 192, 192);
        const Image full = glare_image({ch}, ch, 1);
        const Image split = glare_image({ch}, ch, 4);
        const GlareError e = compare(split, full, 0.5);
        std::printf(
            "sun %.0f deg from the axis: %zu pixels, relative error max %.4f p99 %.4f, energy %.5f, "
            "largest difference %.2e display units\n",
            yaw, e.pixels, e.max, e.p99, e.energy_ratio, e.max_display);
        ASSERT_GT(e.pixels, 1000u) << yaw;
        EXPECT_LT(e.max, 0.06) << yaw;
        EXPECT_LT(e.p99, 0.04) << yaw;
        EXPECT_NEAR(e.energy_ratio, 1.0, 2e-3) << yaw;
        EXPECT_LT(e.max_display, 1e-3) << yaw;  // a quarter of an 8-bit step
    }
}

TEST(GlareHalo, NarrowChannelsEqualOneWideChannelPixelForPixel) {
    // The Sun 3 degrees right of the seam: its core and ring straddle it.
    const EulerDeg o{3.0, 2.0, 0.0};
    const ChannelConfig wide = channel("wide", o, FovDeg{40, 40, 30, 30}, 160, 120);
    const ChannelConfig left = channel("left", o, FovDeg{40, 0, 30, 30}, 80, 120);
    const ChannelConfig right = channel("right", o, FovDeg{0, 40, 30, 30}, 80, 120);
    for (int d : {1, 4}) {
        const Image w = glare_image({wide}, wide, d);
        const Image l = glare_image({left, right}, left, d);
        const Image r = glare_image({left, right}, right, d);
        double worst = 0.0, peak = 0.0;
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x) {
                const float* n = x < 80 ? l.pixel(x, y) : r.pixel(x - 80, y);
                const float* p = w.pixel(x, y);
                for (int c = 0; c < 3; ++c) {
                    worst = std::max(worst, std::abs(double(n[c]) - p[c]) / std::max(1e-30, std::abs(double(p[c]))));
                    peak = std::max(peak, double(p[c]));
                }
            }
        std::printf("downsample %d: worst relative pixel difference %.3g (peak %.3g)\n", d, worst, peak);
        EXPECT_GT(peak, 0.0);
        EXPECT_LT(worst, 1e-4) << "downsample " << d;
    }
}

// What the atmosphere's draw does besides the sky (slave/passes/atmosphere_pass.cpp,
// shaders/atmosphere_lookup.frag): it adds the glare's halo instead of a full-screen draw of its
// own (SKY_HALO), and from inside the air it draws the planet's surface from its map instead of
// the body pass (SKY_HALF, the draw split into sky and ground). On a real headless EGL context
// (llvmpipe on CI), the earth-moon scene from the ground by day with the Sun in view gives the
// same image each way, within float rounding; from orbit, where the atmosphere covers only its
// cap, the glare pass draws the halo and the body pass the surface. The G-buffer is cleared only
// in a frame where some pass reads it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <glm/gtc/quaternion.hpp>

#include "atmosphere/auto_exposure.hpp"
#include "atmosphere/scene_atmospheres.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "glare/glare_sources.hpp"
#include "master_node.hpp"
#include "scene_renderer.hpp"
#include "show_script.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

EglContext& context() { return test::headless_gl("AtmosphereFusedDraws"); }

// The scene and the channel are made once: the snapshot's exposure and glare models keep them.
const SceneConfig& scene() {
    static const SceneConfig s = [] {
        SceneConfig c = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
        for (auto& b : c.bodies) b.texture = "generated:" + b.name;
        return c;
    }();
    return s;
}

const ClusterConfig& one_channel() {
    static const ClusterConfig cluster = [] {
        ClusterConfig c;
        ChannelConfig ch;
        ch.name = "composite";
        ch.fov = FovDeg{45, 45, 45, 45};
        ch.width = ch.height = 96;
        c.channels = {ch};
        c.output.auto_exposure.enabled = true;
        return c;
    }();
    return cluster;
}

glm::dvec3 local(double az_deg, double el_deg) {
    const double az = glm::radians(az_deg), el = glm::radians(el_deg);
    return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
}

// The camera `altitude_m` above the Earth (at the origin, the camera on +z) looking at (az, el),
// the Sun at (az 0, el 40) 1 AU away, finished as the master finishes a frame.
Snapshot snapshot(const SceneConfig& sc, const ClusterConfig& cl, double altitude_m, double look_el_deg) {
    Snapshot s;
    s.bodies.resize(sc.bodies.size());
    for (auto& b : s.bodies) b.id = static_cast<uint16_t>(&b - s.bodies.data());
    s.bodies[sc.find("sun")->id].position_m = 1.495978707e11 * local(0.0, 40.0);
    s.bodies[sc.find("moon")->id].position_m = 3.844e8 * local(60.0, 15.0);
    const glm::dvec3 up(0, 0, 1);
    s.camera_position_m = (sc.find("earth")->radius_m + altitude_m) * up;
    const glm::dvec3 fwd = local(20.0, look_el_deg), right = glm::normalize(glm::cross(fwd, up));
    s.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(right, fwd), -fwd));
    static const SceneAtmospheres atmospheres(sc);
    static const AutoExposure exposure(cl, sc, &atmospheres);
    static const GlareSources glare(sc, &atmospheres);
    finish_frame_snapshot(s, ShowSettings{}, cl, sc, 1, 1.0 / 60.0, &exposure, &glare);
    return s;
}

// Renders the snapshot with the halo added by the atmosphere or not, the surface drawn by it or
// not; returns the image and the renderer's atmosphere counters.
Image render(const SceneConfig& sc, const ClusterConfig& cl, const Snapshot& s, bool halo, bool surface,
             AtmosphereStats& stats, uint64_t* geometry_clears = nullptr) {
    SceneRenderer r(cl, cl.channels[0], sc);
    r.set_halo_with_atmosphere(halo);
    r.set_surface_with_atmosphere(surface);
    Image img = r.render(s);
    stats = r.atmosphere_stats();
    if (geometry_clears) *geometry_clears = r.geometry_clears();
    return img;
}

// The largest difference between two images over the brightest value of the first.
float relative_difference(const Image& a, const Image& b) {
    float brightest = 0.0f, worst = 0.0f;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
        brightest = std::max(brightest, std::abs(a.rgba[i]));
        worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
    }
    return brightest > 0.0f ? worst / brightest : 1.0f;
}

}  // namespace

TEST(AtmosphereFusedDraws, TheHaloAddedByTheAtmosphereIsTheSameImageAsItsOwnDraw) {
    context();
    const SceneConfig& sc = scene();
    ASSERT_TRUE(sc.glare.enabled && sc.glare.halo_downsample > 1) << "the scene must split its glare";
    const ClusterConfig& cl = one_channel();
    const Snapshot s = snapshot(sc, cl, 2.0, 20.0);
    AtmosphereStats fused_stats, own_stats;
    const Image fused = render(sc, cl, s, true, true, fused_stats);
    const Image own = render(sc, cl, s, false, true, own_stats);
    EXPECT_EQ(fused_stats.halos_added, 1);
    EXPECT_EQ(own_stats.halos_added, 0);
    EXPECT_LE(relative_difference(own, fused), 1e-5f);
    // And the halo is there: without the glare the sky around the Sun is darker.
    SceneConfig no_glare = sc;
    no_glare.glare.enabled = false;
    AtmosphereStats unused;
    const Image bare = render(no_glare, cl, s, true, true, unused);
    double with_sum = 0.0, bare_sum = 0.0;
    for (size_t i = 0; i < bare.rgba.size(); i += 4) {
        with_sum += fused.rgba[i + 1];
        bare_sum += bare.rgba[i + 1];
    }
    EXPECT_GT(with_sum, bare_sum * 1.001);
}

TEST(AtmosphereFusedDraws, TheSurfaceDrawnByTheAtmosphereIsTheBodyPasss) {
    context();
    const SceneConfig& sc = scene();
    const ClusterConfig& cl = one_channel();
    const Snapshot s = snapshot(sc, cl, 2.0, 20.0);  // the ground across the lower part
    AtmosphereStats fused_stats, own_stats;
    uint64_t fused_clears = 0, own_clears = 0;
    const Image fused = render(sc, cl, s, true, true, fused_stats, &fused_clears);
    const Image own = render(sc, cl, s, true, false, own_stats, &own_clears);
    EXPECT_EQ(fused_stats.surfaces_drawn, 1);
    EXPECT_EQ(own_stats.surfaces_drawn, 0);
    // Nothing reads the G-buffer when the atmosphere draws the surface: it is not cleared.
    EXPECT_EQ(fused_clears, 0u);
    EXPECT_EQ(own_clears, 1u);
    EXPECT_LE(relative_difference(own, fused), 1e-5f);
    // The map is what was drawn: with the Moon's map on the Earth the ground changes, the sky not.
    SceneConfig other = sc;
    for (auto& b : other.bodies)
        if (b.name == "earth") b.texture = "generated:moon";
    AtmosphereStats unused;
    const Image moon_map = render(other, cl, s, true, true, unused);
    const int ground_row = fused.height - 2, sky_row = 1;  // row 0 of the image is the top
    double ground_change = 0.0, sky_change = 0.0;
    for (int x = 0; x < fused.width; ++x) {
        ground_change =
            std::max(ground_change, std::abs(double(moon_map.pixel(x, ground_row)[1]) - fused.pixel(x, ground_row)[1]) /
                                        fused.pixel(x, ground_row)[1]);
        sky_change = std::max(sky_change, std::abs(double(moon_map.pixel(x, sky_row)[1]) - fused.pixel(x, sky_row)[1]));
    }
    EXPECT_GT(ground_change, 0.01);
    EXPECT_EQ(sky_change, 0.0);
}

TEST(AtmosphereFusedDraws, FromOrbitTheGlareAndBodyPassesDrawTheirOwn) {
    context();
    const SceneConfig& sc = scene();
    const ClusterConfig& cl = one_channel();
    AtmosphereStats stats;
    uint64_t clears = 0;
    render(sc, cl, snapshot(sc, cl, 400.0e3, 0.0), true, true, stats, &clears);
    EXPECT_EQ(stats.halos_added, 0);     // the atmosphere seen from outside covers only its cap
    EXPECT_EQ(stats.surfaces_drawn, 0);  // and draws no surface
    EXPECT_EQ(clears, 1u);               // but reads the G-buffer, which is cleared
}

// What the atmosphere's draw does besides the sky (slave/passes/atmosphere_pass.cpp,
// shaders/atmosphere_lookup.frag): it adds the glare's halo instead of a full-screen draw of its
// own (SKY_HALO), and from inside the air it draws the planet's surface from its map instead of
// the body pass (SKY_HALF, the draw split into sky and ground). On a real headless EGL context
// (llvmpipe on CI), the earth-moon scene from the ground by day with the Sun in view gives the
// same image each way, within float rounding; from orbit, where the atmosphere covers only its
// cap, the glare pass draws the halo, and the atmosphere draws the surface from the map unless a
// body could be in front of the air. The G-buffer is cleared only in a frame where some pass
// reads it.
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
#include "support/earth_moon_scene.hpp"
#include "support/headless_gl.hpp"
#include "support/image_difference.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

EglContext& context() { return test::headless_gl("AtmosphereFusedDraws"); }

const SceneConfig& scene() { return test::earth_moon_scene(); }

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

glm::dvec3 local(double az_deg, double el_deg) { return test::horizon_direction(az_deg, el_deg); }

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

using test::relative_difference;

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

TEST(AtmosphereFusedDraws, FromOrbitTheSurfaceDrawnByTheAtmosphereIsTheBodyPasssButNotTheHalo) {
    context();
    const SceneConfig& sc = scene();
    const ClusterConfig& cl = one_channel();
    const Snapshot s = snapshot(sc, cl, 400.0e3, -15.0);  // the limb across the channel
    AtmosphereStats fused_stats, own_stats;
    uint64_t fused_clears = 0, own_clears = 0;
    const Image fused = render(sc, cl, s, true, true, fused_stats, &fused_clears);
    const Image own = render(sc, cl, s, true, false, own_stats, &own_clears);
    EXPECT_EQ(fused_stats.halos_added, 0);     // the atmosphere seen from outside covers only its cap
    EXPECT_EQ(fused_stats.surfaces_drawn, 1);  // but relights the surface from the map (SKY_MAP)
    EXPECT_EQ(own_stats.surfaces_drawn, 0);
    EXPECT_EQ(fused_clears, 0u);  // so nothing reads the G-buffer
    EXPECT_EQ(own_clears, 1u);
    EXPECT_LE(relative_difference(own, fused), 1e-5f);
}

TEST(AtmosphereFusedDraws, ABodyInFrontOfTheAirFromOutsideLeavesTheSurfaceToTheBodyPass) {
    context();
    const SceneConfig& sc = scene();
    const ClusterConfig& cl = one_channel();
    // From 50 000 km, looking down at the Earth, the Moon 20 000 km away in front of its limb:
    // outside the air, nearer than it, and over it on screen.
    Snapshot s = snapshot(sc, cl, 5.0e7, -89.9);
    const glm::dvec3 down(0, 0, -1), aside = glm::normalize(glm::dvec3(1, 0, 0));
    const double limb_rad = std::asin(sc.find("earth")->radius_m / glm::length(s.camera_position_m));
    s.bodies[sc.find("moon")->id].position_m =
        s.camera_position_m + 2.0e7 * (std::cos(limb_rad) * down + std::sin(limb_rad) * aside);
    AtmosphereStats stats;
    uint64_t clears = 0;
    render(sc, cl, s, true, true, stats, &clears);
    EXPECT_EQ(stats.surfaces_drawn, 0);
    EXPECT_EQ(clears, 1u);  // the atmosphere reads the G-buffer: the Moon's pixels keep the Moon
    // The same view with the Moon beyond the Earth, on the far side of the air: drawn from the map.
    s.bodies[sc.find("moon")->id].position_m = -3.844e8 * glm::normalize(s.camera_position_m);
    render(sc, cl, s, true, true, stats, &clears);
    EXPECT_EQ(stats.surfaces_drawn, 1);
    EXPECT_EQ(clears, 0u);
}

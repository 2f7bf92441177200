// The glare's halo added by the atmosphere's draw (slave/passes/atmosphere_pass.cpp, SKY_HALO in
// shaders/atmosphere_lookup.frag) instead of a full-screen draw of its own: on a real headless EGL
// context (llvmpipe on CI), the earth-moon scene from the ground by day with the Sun in view gives
// the same image both ways, within float rounding; from orbit, where the atmosphere covers only
// its cap, the glare pass keeps drawing the halo.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

EglContext& context() { return test::headless_gl("GlareHaloComposite"); }

SceneConfig scene() {
    SceneConfig s = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    for (auto& b : s.bodies) b.texture = "generated:" + b.name;
    return s;
}

ClusterConfig one_channel() {
    ClusterConfig c;
    ChannelConfig ch;
    ch.name = "composite";
    ch.fov = FovDeg{45, 45, 45, 45};
    ch.width = ch.height = 96;
    c.channels = {ch};
    c.output.auto_exposure.enabled = true;
    return c;
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

// Renders the snapshot with the halo added by the atmosphere or not; returns the image and the
// number of draws that added it.
Image render(const SceneConfig& sc, const ClusterConfig& cl, const Snapshot& s, bool with_atmosphere, long& added) {
    SceneRenderer r(cl, cl.channels[0], sc);
    r.set_halo_with_atmosphere(with_atmosphere);
    Image img = r.render(s);
    added = r.atmosphere_stats().halos_added;
    return img;
}

}  // namespace

TEST(GlareHaloComposite, AddedByTheAtmosphereItIsTheSameImageAsItsOwnDraw) {
    context();
    const SceneConfig sc = scene();
    ASSERT_TRUE(sc.glare.enabled && sc.glare.halo_downsample > 1) << "the scene must split its glare";
    const ClusterConfig cl = one_channel();
    const Snapshot s = snapshot(sc, cl, 2.0, 20.0);
    long added_fused = 0, added_own = 0;
    const Image fused = render(sc, cl, s, true, added_fused);
    const Image own = render(sc, cl, s, false, added_own);
    EXPECT_EQ(added_fused, 1);
    EXPECT_EQ(added_own, 0);
    float brightest = 0.0f, worst = 0.0f;
    for (size_t i = 0; i < own.rgba.size(); ++i) {
        brightest = std::max(brightest, std::abs(own.rgba[i]));
        worst = std::max(worst, std::abs(fused.rgba[i] - own.rgba[i]));
    }
    ASSERT_GT(brightest, 0.0f);
    EXPECT_LE(worst, 1e-5f * brightest) << "largest difference " << worst << " of " << brightest;
    // And the halo is there: without the glare the sky around the Sun is darker.
    SceneConfig no_glare = sc;
    no_glare.glare.enabled = false;
    long unused = 0;
    const Image bare = render(no_glare, cl, s, true, unused);
    double with_sum = 0.0, bare_sum = 0.0;
    for (size_t i = 0; i < bare.rgba.size(); i += 4) {
        with_sum += fused.rgba[i + 1];
        bare_sum += bare.rgba[i + 1];
    }
    EXPECT_GT(with_sum, bare_sum * 1.001);
}

TEST(GlareHaloComposite, FromOrbitTheGlarePassDrawsTheHaloItself) {
    context();
    const SceneConfig sc = scene();
    const ClusterConfig cl = one_channel();
    long added = 0;
    render(sc, cl, snapshot(sc, cl, 400.0e3, 0.0), true, added);
    EXPECT_EQ(added, 0);  // the atmosphere seen from outside covers only its cap
}

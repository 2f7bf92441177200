// The renderer's opt-in pass timing (SceneRenderer::set_pass_timing, slave/scene_renderer.hpp)
// on a real headless EGL context: off, nothing is recorded; on, every pass of the list has one
// entry in run order, the frame's total holds the passes, and render() adds its read-back. Only
// the structure of the timings is checked, never how long anything took.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "scene_renderer.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

EglContext& context() { return test::headless_gl("PassTiming"); }

// A Sun, an airless planet filling part of a 32^2 view, one bright star, glare on.
struct Frame {
    SceneConfig scene;
    ClusterConfig cluster;
    ChannelConfig channel;
    Snapshot snap;

    Frame() {
        const std::string dir = test::scratch_dir("PassTiming");
        test::write_text(dir + "/stars.csv", "ra_deg,dec_deg,vmag,bv,name\n10.0,10.0,1.0,0.6,Bright\n");
        test::write_text(dir + "/scene.json", R"({ "bodies": [
            { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 5.8e4,
              "texture": "generated:sun" },
            { "name": "moon", "kind": "moon", "ephemeris": "moon", "radius_m": 1.7374e6,
              "texture": "generated:moon", "albedo": 0.12 } ],
          "stars": { "catalog": "stars.csv", "magnitude_limit": 6.0 },
          "glare": { "enabled": true } })");
        scene = load_scene_config(dir + "/scene.json");
        channel.name = "timing";
        channel.width = channel.height = 32;
        channel.fov = FovDeg{30, 30, 30, 30};
        cluster.channels = {channel};
        snap.frame = 1;
        snap.settings.exposure = 1.0f;
        snap.bodies = {BodyState{0, glm::dvec3(1.0e10, 0.0, -1.0e11), {1, 0, 0, 0}},
                       BodyState{1, glm::dvec3(0.0, 0.0, -1.0e7), {1, 0, 0, 0}}};
    }
};

double sum_of_passes(const FrameTimings& t) {
    double s = 0.0;
    for (const auto& [name, ms] : t.passes_ms) {
        EXPECT_GE(ms, 0.0) << name;
        s += ms;
    }
    return s;
}

}  // namespace

TEST(PassTiming, OffByDefaultRecordsNothing) {
    context();
    const Frame f;
    SceneRenderer r(f.cluster, f.channel, f.scene);
    r.draw(f.snap);
    r.render(f.snap);
    EXPECT_TRUE(r.last_frame_timings().passes_ms.empty());
    EXPECT_EQ(r.last_frame_timings().frame_ms, 0.0);
    EXPECT_EQ(r.last_frame_timings().read_back_ms, 0.0);
}

TEST(PassTiming, EveryPassOnceInRunOrderWithinTheFrame) {
    context();
    const Frame f;
    SceneRenderer r(f.cluster, f.channel, f.scene);
    r.set_pass_timing(true);
    r.draw(f.snap);
    const FrameTimings drawn = r.last_frame_timings();
    std::vector<std::string> names;
    for (const auto& p : drawn.passes_ms) names.push_back(p.first);
    EXPECT_EQ(names, r.pass_names());
    EXPECT_EQ(drawn.read_back_ms, 0.0);
    EXPECT_GE(drawn.frame_ms, sum_of_passes(drawn));

    r.render(f.snap);  // the read-back is counted into this frame, not the one before
    const FrameTimings read = r.last_frame_timings();
    EXPECT_EQ(read.passes_ms.size(), drawn.passes_ms.size());
    EXPECT_GT(read.read_back_ms, 0.0);
    EXPECT_GE(read.frame_ms, sum_of_passes(read) + read.read_back_ms);

    r.set_pass_timing(false);  // the last timed frame stays, later frames are not recorded
    r.draw(f.snap);
    EXPECT_EQ(r.last_frame_timings().read_back_ms, read.read_back_ms);
    EXPECT_EQ(r.last_frame_timings().frame_ms, read.frame_ms);
}

// The master keeps the camera above the relief (common/terrain/terrain_clearance): a camera under
// the ground, or closer to it than the clearance, is lifted along the vertical to the clearance;
// one above it, or far away, is left exactly where it was; bodies without terrain are ignored.
// Walking (the director's live navigation), the eye keeps its height above the relief, and a goto
// with a height lands that high above it.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "control/control_command.hpp"
#include "director.hpp"
#include "show_script.hpp"
#include "support/earth_moon_scene.hpp"
#include "terrain/terrain_clearance.hpp"

using namespace cupola;

TEST(TerrainClearance, ACameraUnderTheReliefIsLiftedAndOneAboveItIsLeftAlone) {
    SceneConfig sc = test::earth_moon_scene();
    const terrain::TerrainClearance none(sc);
    EXPECT_FALSE(none.any());
    BodyConfig& earth = sc.bodies[sc.find("earth")->id];
    earth.terrain.present = true;
    earth.terrain.procedural_wavelength_m = 60e3;
    earth.terrain.procedural_amplitude_m = 1600.0;
    const terrain::TerrainClearance clearance(sc, 2.0);
    ASSERT_TRUE(clearance.any());
    BodyState state;
    state.id = earth.id;
    state.position_m = glm::dvec3(1.4e11, -3e10, 2e9);  // far from the origin
    state.orientation = glm::angleAxis(0.7, glm::normalize(glm::dvec3(0.2, 0.3, 1.0)));
    const std::vector<BodyState> bodies = {state};
    int tested = 0;
    for (double lon = -170.0; lon < 180.0; lon += 37.0)
        for (double lat = -60.0; lat <= 60.0; lat += 30.0) {
            const double la = glm::radians(lat), lo = glm::radians(lon);
            const glm::dvec3 dir_body(std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la));
            const glm::dvec3 dir = state.orientation * dir_body;
            const double h = clearance.ground_height_m(state, state.position_m + dir * earth.radius_m);
            EXPECT_NE(h, 0.0);
            // Under the ground: lifted to 2 m above it, along the vertical.
            const glm::dvec3 under = state.position_m + dir * (earth.radius_m + h - 50.0);
            const glm::dvec3 lifted = clearance.keep_above(bodies, under);
            EXPECT_NEAR(glm::length(lifted - state.position_m), earth.radius_m + h + 2.0, 1e-3);
            EXPECT_LT(glm::length(glm::normalize(lifted - state.position_m) - dir), 1e-10);  // metres of 1e11
            // Above it: not moved at all.
            const glm::dvec3 above = state.position_m + dir * (earth.radius_m + h + 3.0);
            EXPECT_EQ(clearance.keep_above(bodies, above), above);
            ++tested;
        }
    EXPECT_GT(tested, 20);
    EXPECT_EQ(clearance.lifts(), static_cast<uint64_t>(tested));
    const glm::dvec3 far = state.position_m + glm::dvec3(0.0, 0.0, 4e7);
    EXPECT_EQ(clearance.keep_above(bodies, far), far);
}

TEST(TerrainClearance, WalkingTheEyeKeepsItsHeightAboveTheRelief) {
    ClusterConfig cluster = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    cluster.frame_rate_hz = 0;
    SceneConfig scene = load_scene_config(cluster.scene_file);
    BodyConfig& earth = scene.bodies[scene.find("earth")->id];
    earth.terrain.present = true;
    earth.terrain.procedural_wavelength_m = 40e3;
    earth.terrain.procedural_amplitude_m = 3000.0;
    const ShowScript show = ShowScript::load(cluster.show_file, scene);
    Director director(cluster, scene, show);
    const terrain::TerrainClearance ground(scene);
    director.apply(parse_control_line("mode walk earth"), 1);
    NavSample walking;
    walking.connected = true;
    walking.axes.forward = 1.0;
    double lowest = 1e30, highest = -1e30, eye = -1.0;
    for (uint64_t f = 1; f < 200; ++f) {
        const Snapshot s = director.frame(f, walking).snapshot;
        const BodyState& e = s.bodies[earth.id];
        const double over_sphere = glm::length(s.camera_position_m - e.position_m) - earth.radius_m;
        const double ground_m = ground.ground_height_m(e, s.camera_position_m);
        if (eye < 0.0) eye = over_sphere - ground_m;  // the walker's eye height
        EXPECT_NEAR(over_sphere - ground_m, eye, 0.01) << "frame " << f;
        lowest = std::min(lowest, ground_m);
        highest = std::max(highest, ground_m);
    }
    EXPECT_GT(eye, 0.5);
    EXPECT_LT(eye, 10.0);
    EXPECT_GT(highest - lowest, 1.0) << "the walk must cross some relief";
}

namespace {

struct TerrainDirector {
    ClusterConfig cluster = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    SceneConfig scene;
    uint16_t earth = 0;
    TerrainDirector() {
        cluster.frame_rate_hz = 0;
        scene = load_scene_config(cluster.scene_file);
        earth = scene.find("earth")->id;
        BodyConfig& e = scene.bodies[earth];
        e.terrain.present = true;
        e.terrain.procedural_wavelength_m = 40e3;
        e.terrain.procedural_amplitude_m = 3000.0;
    }
    // The camera's height above the ground (relief) in a frame.
    double height(const Snapshot& s, const terrain::TerrainClearance& ground) const {
        const BodyState& e = s.bodies[earth];
        const double over_sphere = glm::length(s.camera_position_m - e.position_m) - scene.bodies[earth].radius_m;
        return over_sphere - ground.ground_height_m(e, s.camera_position_m);
    }
};

}  // namespace

TEST(TerrainClearance, GotoWithAHeightLandsThatHighAboveTheRelief) {
    TerrainDirector t;
    const ShowScript show = ShowScript::load(t.cluster.show_file, t.scene);
    const terrain::TerrainClearance ground(t.scene);
    for (const char* rate : {"0", "1", "600"}) {
        Director director(t.cluster, t.scene, show);
        director.apply(parse_control_line(std::string("time rate ") + rate), 1);
        uint64_t f = 1;
        struct Goto {
            int seconds;
            double height_m;
        };
        for (const Goto go : {Goto{0, 500.0}, Goto{2, 40.0}, Goto{1, 2500.0}}) {
            const std::string line =
                "goto earth " + std::to_string(go.seconds) + " height " + std::to_string(go.height_m);
            director.apply(parse_control_line(line), f);
            const uint64_t landing = f + static_cast<uint64_t>(std::llround(go.seconds / director.frame_interval_s()));
            Snapshot s;
            for (; f <= landing; ++f) s = director.frame(f, NavSample{}).snapshot;
            // A third of a percent: what the ground does in one frame under the camera at 600x.
            EXPECT_NEAR(t.height(s, ground), go.height_m, 0.003 * go.height_m + 1e-3)
                << line << " at time rate " << rate;
        }
    }
    // Without a height, goto keeps to four radii from the centre, whatever the relief.
    Director director(t.cluster, t.scene, show);
    director.apply(parse_control_line("goto earth 0"), 1);
    const Snapshot s = director.frame(1, NavSample{}).snapshot;
    EXPECT_NEAR(glm::length(s.camera_position_m - s.bodies[t.earth].position_m), 4.0 * t.scene.bodies[t.earth].radius_m,
                1e-3);
}

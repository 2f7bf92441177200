// Show interpolation, time conversion and the ephemeris against known values.
#include <gtest/gtest.h>

#include <cmath>

#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "scene/ephemeris.hpp"
#include "scene/sim_time.hpp"
#include "show_script.hpp"
#include "support/test_support.hpp"

using namespace cupola;

TEST(SimTime, J2000EpochAndLeapSeconds) {
    // J2000.0 is 2000-01-01T12:00:00 TT = 11:58:55.816 UTC (TT-UTC = 64.184 s then).
    EXPECT_NEAR(utc_iso_to_j2000_seconds("2000-01-01T11:58:55.816Z"), 0.0, 1e-6);
    // One day later in UTC is 86400 s later (no leap second that day).
    EXPECT_NEAR(utc_iso_to_j2000_seconds("2000-01-02T11:58:55.816Z"), 86400.0, 1e-6);
    // Across the 2016-12-31 leap second, 1 UTC second apart is 2 SI seconds.
    double a = utc_iso_to_j2000_seconds("2016-12-31T23:59:59Z");
    double b = utc_iso_to_j2000_seconds("2017-01-01T00:00:00Z");
    EXPECT_NEAR(b - a, 2.0, 1e-6);
    EXPECT_THROW(utc_iso_to_j2000_seconds("yesterday"), std::invalid_argument);
    EXPECT_THROW(utc_iso_to_j2000_seconds("2024-13-01T00:00:00Z"), std::invalid_argument);
}

TEST(AnalyticEphemeris, DistancesAndSeasons) {
    SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    const BodyConfig& earth = *scene.find("earth");
    const BodyConfig& moon = *scene.find("moon");
    // Perihelion early January (0.9833 AU), aphelion early July (1.0167 AU).
    double tp = utc_iso_to_j2000_seconds("2024-01-03T00:00:00Z");
    double ta = utc_iso_to_j2000_seconds("2024-07-05T00:00:00Z");
    EXPECT_NEAR(glm::length(body_state(earth, tp).position_m) / kAstronomicalUnit_m, 0.9833, 0.0005);
    EXPECT_NEAR(glm::length(body_state(earth, ta).position_m) / kAstronomicalUnit_m, 1.0167, 0.0005);
    // March equinox 2024-03-20 03:06 UTC: the Sun is at the equinox OF DATE. In our J2000 axes
    // the equinox has precessed by 50.29"/yr x 24.2 yr = 0.338 deg of ecliptic longitude, so the
    // Sun's J2000 declination is asin(sin(-0.338 deg) sin(23.44 deg)) = -0.134 deg and the Earth,
    // seen from the Sun, sits at declination +0.134 deg.
    double te = utc_iso_to_j2000_seconds("2024-03-20T03:06:00Z");
    glm::dvec3 e = glm::normalize(body_state(earth, te).position_m);
    EXPECT_NEAR(e.x, -1.0, 1e-4);
    EXPECT_NEAR(glm::degrees(std::asin(e.z)), 0.134, 0.02);
    // The Moon a day after perigee (7 April 2024): 359 783 km from the Earth's centre by ERFA's
    // eraMoon98 (its geocentric distance ranges over 356 000-407 000 km).
    double t = utc_iso_to_j2000_seconds("2024-04-08T18:00:00Z");
    glm::dvec3 rel = body_state(moon, t).position_m - body_state(earth, t).position_m;
    EXPECT_NEAR(glm::length(rel), 3.5978e8, 2e5);
    // New moon on 2024-04-08 (the total solar eclipse): Moon and Sun in the same direction
    // from the Earth, to the accuracy of a circular orbit (a few degrees).
    glm::dvec3 sun_dir = glm::normalize(-body_state(earth, t).position_m);
    double sep = glm::degrees(std::acos(glm::dot(sun_dir, glm::normalize(rel))));
    EXPECT_LT(sep, 8.0);
}

TEST(ShowScript, InterpolatesTimeAndCameraDeterministically) {
    ClusterConfig cfg = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    SceneConfig scene = load_scene_config(cfg.scene_file);
    ShowScript show = ShowScript::load(cfg.show_file, scene);
    ASSERT_EQ(show.keyframes().size(), 2u);
    const auto& k0 = show.keyframes()[0];
    const auto& k1 = show.keyframes()[1];
    Snapshot a = show.evaluate(k0.at_s, scene);
    Snapshot m = show.evaluate(0.5 * (k0.at_s + k1.at_s), scene);
    Snapshot b = show.evaluate(k1.at_s, scene);
    EXPECT_DOUBLE_EQ(a.sim_time_s, k0.sim_time_s);
    EXPECT_DOUBLE_EQ(b.sim_time_s, k1.sim_time_s);
    EXPECT_NEAR(m.sim_time_s, 0.5 * (k0.sim_time_s + k1.sim_time_s), 1e-6);
    // The camera rides with the Earth at the keyframe offset.
    const glm::dvec3 earth_a = a.bodies[scene.find("earth")->id].position_m;
    EXPECT_NEAR(glm::length(a.camera_position_m - earth_a - k0.camera.offset_m), 0.0, 1e-3);
    // The Earth appears at the requested elevation above the front horizon, straight ahead.
    const glm::dmat3 cam = glm::mat3_cast(a.camera_orientation);
    const glm::dvec3 to_earth = glm::transpose(cam) * glm::normalize(earth_a - a.camera_position_m);
    EXPECT_NEAR(glm::degrees(std::asin(to_earth.y)), k0.camera.target_elevation_deg, 1e-6);
    EXPECT_NEAR(to_earth.x, 0.0, 1e-9);
    EXPECT_LT(to_earth.z, 0.0);
    // Same show time, same snapshot: every run (and every process) agrees.
    EXPECT_EQ(show.evaluate(3.21, scene), show.evaluate(3.21, scene));
    EXPECT_NEAR(glm::length(m.camera_orientation), 1.0, 1e-12);
}

TEST(ShowScript, ErrorsNameTheField) {
    SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    const std::string dir = test::scratch_dir("show");
    test::write_text(dir + "/bad.json", R"({"keyframes":[{"at_s":0,"time_utc":"2024-04-08T12:00:00Z",
        "camera":{"anchor":"mars","look_at":"earth"}}]})");
    try {
        ShowScript::load(dir + "/bad.json", scene);
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "keyframes[0].camera.anchor");
    }
    test::write_text(dir + "/order.json", R"({"keyframes":[
        {"at_s":5,"time_utc":"2024-04-08T12:00:00Z","camera":{"look_at":"earth"}},
        {"at_s":5,"time_utc":"2024-04-08T13:00:00Z","camera":{"look_at":"earth"}}]})");
    try {
        ShowScript::load(dir + "/order.json", scene);
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "keyframes[1].at_s");
    }
    test::write_text(dir + "/time.json", R"({"keyframes":[{"at_s":0,"time_utc":"noon","camera":{"look_at":"earth"}}]})");
    try {
        ShowScript::load(dir + "/time.json", scene);
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "keyframes[0].time_utc");
    }
}

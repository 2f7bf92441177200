// Show interpolation, time conversion and the ephemeris against known values.
#include <gtest/gtest.h>

#include <cmath>

#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "scene/ephemeris.hpp"
#include "scene/sim_time.hpp"
#include "eclipse/shadow_casters.hpp"
#include "master_node.hpp"
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
    test::write_text(dir + "/time.json",
                     R"({"keyframes":[{"at_s":0,"time_utc":"noon","camera":{"look_at":"earth"}}]})");
    try {
        ShowScript::load(dir + "/time.json", scene);
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "keyframes[0].time_utc");
    }
}

namespace {
// A two-key show on the Earth-Moon scene: one hour of simulation time over 10 show seconds, the
// camera moving 1000 km along x, with the given easings and events.
ShowScript easing_show(const SceneConfig& scene, const std::string& dir, const std::string& camera_easing,
                       const std::string& time_easing, const std::string& events = "") {
    test::write_text(dir + "/show.json", R"({"frame_interval_s": 0.5, "keyframes":[
        {"at_s":0,"time_utc":"2024-04-08T12:00:00Z","easing":")" +
                                             camera_easing + R"(","time_easing":")" + time_easing + R"(",
         "camera":{"anchor":"earth","offset_m":[2e7,0,0],"look_at":"earth"}},
        {"at_s":10,"time_utc":"2024-04-08T13:00:00Z",
         "camera":{"anchor":"earth","offset_m":[2.1e7,0,0],"look_at":"earth"}}])" +
                                             (events.empty() ? "" : ", \"events\": " + events) + "}");
    return ShowScript::load(dir + "/show.json", scene);
}
double camera_x_from_earth(const Snapshot& s, const SceneConfig& scene) {
    return s.camera_position_m.x - s.bodies[scene.find("earth")->id].position_m.x;
}
}  // namespace

TEST(ShowScript, EasingShapesCameraAndTimeBetweenKeys) {
    SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    const std::string dir = test::scratch_dir("show_easing");
    const double t0 = utc_iso_to_j2000_seconds("2024-04-08T12:00:00Z");
    struct Case {
        const char* name;
        double at_quarter;  // eased progress at f = 0.25
    };
    for (const Case c : {Case{"linear", 0.25}, Case{"ease_in", 0.0625}, Case{"ease_out", 0.4375},
                         Case{"ease_in_out", 0.15625}, Case{"hold", 0.0}}) {
        SCOPED_TRACE(c.name);
        const ShowScript cam = easing_show(scene, dir, c.name, "linear");
        // Camera: 1000 km between the keys, eased; time stays linear.
        const Snapshot s = cam.evaluate(2.5, scene);
        EXPECT_NEAR(camera_x_from_earth(s, scene) - 2e7, 1e6 * c.at_quarter, 1e-3);
        EXPECT_NEAR(s.sim_time_s - t0, 900.0, 1e-6);
        // Both ends are reached exactly.
        EXPECT_NEAR(camera_x_from_earth(cam.evaluate(0.0, scene), scene), 2e7, 1e-3);
        EXPECT_NEAR(camera_x_from_earth(cam.evaluate(10.0, scene), scene), 2.1e7, 1e-3);
        // Time easing: the clock follows the same curve.
        const ShowScript tim = easing_show(scene, dir, "linear", c.name);
        EXPECT_NEAR(tim.evaluate(2.5, scene).sim_time_s - t0, 3600.0 * c.at_quarter, 1e-6);
        EXPECT_NEAR(tim.evaluate(10.0, scene).sim_time_s - t0, 3600.0, 1e-6);
    }
    // The default is the old behaviour: camera ease in-out, time linear.
    test::write_text(dir + "/default.json", R"({"keyframes":[
        {"at_s":0,"time_utc":"2024-04-08T12:00:00Z","camera":{"anchor":"earth","offset_m":[2e7,0,0],"look_at":"earth"}},
        {"at_s":10,"time_utc":"2024-04-08T13:00:00Z","camera":{"anchor":"earth","offset_m":[2.1e7,0,0],"look_at":"earth"}}]})");
    const ShowScript def = ShowScript::load(dir + "/default.json", scene);
    EXPECT_NEAR(camera_x_from_earth(def.evaluate(2.5, scene), scene) - 2e7, 1e6 * 0.15625, 1e-3);
    EXPECT_NEAR(def.evaluate(2.5, scene).sim_time_s - t0, 900.0, 1e-6);
}

TEST(ShowScript, EventsSwitchRenderSettingsAtTheirTime) {
    SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    const std::string dir = test::scratch_dir("show_events");
    const ShowScript show = easing_show(scene, dir, "linear", "linear", R"([
        {"at_s": 2, "shadow_mode": "illustrative"},
        {"at_s": 4, "exposure": 2.5, "star_magnitude_limit": 4.0},
        {"at_s": 6, "exposure": "auto", "shadow_mode": "off"},
        {"at_s": 8, "twinkle": "forced"},
        {"at_s": 8.5, "bortle": 8, "show": ["constellations", "grid equatorial"]},
        {"at_s": 9.5, "hide": ["constellations"]}])");
    EXPECT_EQ(shadow_mode_of(show.evaluate(1.99, scene).settings.flags), scene.shadows.mode);
    EXPECT_EQ(twinkle_mode_of(show.evaluate(7.9, scene).settings.flags), scene.stars.twinkle);  // the scene's
    EXPECT_EQ(twinkle_mode_of(show.evaluate(8.0, scene).settings.flags), TwinkleMode::Forced);
    EXPECT_EQ(shadow_mode_of(show.evaluate(2.0, scene).settings.flags), ShadowMode::Illustrative);
    EXPECT_FALSE(show.settings_at(3.9).exposure);
    ASSERT_TRUE(show.settings_at(4.0).exposure);
    EXPECT_FLOAT_EQ(*show.settings_at(5.0).exposure, 2.5f);
    EXPECT_FLOAT_EQ(*show.settings_at(5.0).star_magnitude_limit, 4.0f);
    EXPECT_FALSE(show.settings_at(6.0).exposure);                        // back to the cluster's exposure
    EXPECT_FLOAT_EQ(*show.settings_at(6.0).star_magnitude_limit, 4.0f);  // kept
    EXPECT_EQ(shadow_mode_of(show.evaluate(7.0, scene).settings.flags), ShadowMode::Off);
    EXPECT_DOUBLE_EQ(show.duration_s(), 10.0);
    EXPECT_EQ(*show.settings_at(9.0).twinkle, TwinkleMode::Forced);
    // Overlays switched by events: none until 8.5 s, then two, then one of them hidden again.
    EXPECT_FALSE(show.settings_at(8.4).overlays[static_cast<size_t>(OverlayKind::Constellations)]);
    EXPECT_TRUE(*show.settings_at(9.0).overlays[static_cast<size_t>(OverlayKind::Constellations)]);
    EXPECT_TRUE(*show.settings_at(9.0).overlays[static_cast<size_t>(OverlayKind::GridEquatorial)]);
    EXPECT_FALSE(*show.settings_at(9.6).overlays[static_cast<size_t>(OverlayKind::Constellations)]);
    EXPECT_TRUE(*show.settings_at(9.6).overlays[static_cast<size_t>(OverlayKind::GridEquatorial)]);

    // The master turns them into the snapshot every channel receives.
    ClusterConfig cfg = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    cfg.frame_rate_hz = 0;                                         // frame N = show time N x 0.5 s
    const Snapshot f9 = make_frame_snapshot(cfg, scene, show, 9);  // 4.5 s
    EXPECT_FLOAT_EQ(f9.settings.exposure, 2.5f);
    EXPECT_FLOAT_EQ(f9.settings.star_magnitude_limit, 4.0f);
    EXPECT_EQ(shadow_mode_of(f9.settings.flags), ShadowMode::Illustrative);
    const Snapshot f13 = make_frame_snapshot(cfg, scene, show, 13);  // 6.5 s
    EXPECT_FLOAT_EQ(f13.settings.exposure, static_cast<float>(cfg.output.exposure));
    EXPECT_EQ(shadow_mode_of(f13.settings.flags), ShadowMode::Off);
    // The twinkle clock is show time (frame x interval).
    EXPECT_FLOAT_EQ(f13.settings.twinkle_time_s, 6.5f);
    EXPECT_EQ(twinkle_mode_of(make_frame_snapshot(cfg, scene, show, 17).settings.flags), TwinkleMode::Forced);
    // The night sky's brightness: none in the scene, a city's (Bortle 8, 18 mag/arcsec^2) from 8.5 s.
    EXPECT_FLOAT_EQ(make_frame_snapshot(cfg, scene, show, 16).settings.night_sky_cd_m2, 0.0f);
    EXPECT_NEAR(make_frame_snapshot(cfg, scene, show, 17).settings.night_sky_cd_m2, 1.08e5 * std::pow(10.0, -7.2),
                1e-6);
}

TEST(ShowScript, BadEasingsAndEventsNameTheField) {
    SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    const std::string dir = test::scratch_dir("show_bad_events");
    auto field_of = [&](const std::string& text) {
        test::write_text(dir + "/s.json", text);
        try {
            ShowScript::load(dir + "/s.json", scene);
        } catch (const ConfigError& e) {
            return e.field();
        }
        return std::string("(accepted)");
    };
    const std::string key = R"({"at_s":0,"time_utc":"2024-04-08T12:00:00Z","camera":{"look_at":"earth"}})";
    EXPECT_EQ(
        field_of(
            R"({"keyframes":[{"at_s":0,"time_utc":"2024-04-08T12:00:00Z","easing":"bouncy","camera":{"look_at":"earth"}}]})"),
        "keyframes[0].easing");
    EXPECT_EQ(field_of(R"({"keyframes":[)" + key + R"(],"events":[{"at_s":1,"shadow_mode":"sharp"}]})"),
              "events[0].shadow_mode");
    EXPECT_EQ(field_of(R"({"keyframes":[)" + key + R"(],"events":[{"at_s":1,"exposure":-1}]})"), "events[0].exposure");
    EXPECT_EQ(field_of(R"({"keyframes":[)" + key + R"(],"events":[{"at_s":1,"exposure":"bright"}]})"),
              "events[0].exposure");
    EXPECT_EQ(field_of(R"({"keyframes":[)" + key + R"(],"events":[{"at_s":1}]})"), "events[0].at_s");
    EXPECT_EQ(field_of(R"({"keyframes":[)" + key + R"(],"events":[{"at_s":1,"exposure":1,"glow":1}]})"),
              "events[0].glow");
    EXPECT_EQ(field_of(R"({"keyframes":[)" + key + R"(],"events":[{"at_s":1,"show":["grid galactic"]}]})"),
              "events[0].show");
    EXPECT_EQ(field_of(R"({"keyframes":[)" + key + R"(],"events":[{"at_s":1,"bortle":12}]})"), "events[0].bortle");
    EXPECT_EQ(field_of(R"({"keyframes":[)" + key + R"(],"events":[{"at_s":1,"bortle":3,"sky_brightness":20}]})"),
              "events[0].bortle");
}

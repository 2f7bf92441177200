// The master's control channel: the command language, the socket server (real Unix sockets)
// and the director that turns commands and device input into snapshots.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>

#include "config/cluster_config.hpp"
#include "control/control_command.hpp"
#include "control/control_server.hpp"
#include "director.hpp"
#include "eclipse/shadow_casters.hpp"
#include "master_node.hpp"
#include "scene/ephemeris.hpp"
#include "scene/night_sky.hpp"
#include "scene/sim_time.hpp"
#include "support/control_client.hpp"
#include "support/test_support.hpp"

using namespace cupola;
using test::ControlClient;

namespace {

std::string parse_error(const std::string& line) {
    try {
        parse_control_line(line);
    } catch (const ControlError& e) {
        return e.what();
    }
    return "(accepted)";
}

// Waits until the server has `n` requests and returns them.
std::vector<ControlRequest> take_n(ControlServer& server, size_t n) {
    std::vector<ControlRequest> all;
    for (int i = 0; i < 500 && all.size() < n; ++i) {
        auto got = server.take();
        all.insert(all.end(), got.begin(), got.end());
        if (all.size() < n) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return all;
}

struct DirectorFixture : ::testing::Test {
    void SetUp() override {
        cluster = load_cluster_config(test::source_path("configs/dome-4ch.json"));
        cluster.frame_rate_hz = 0;  // frame interval = the show's (0.04 s)
        scene = load_scene_config(cluster.scene_file);
        show = std::make_unique<ShowScript>(ShowScript::load(cluster.show_file, scene));
        director = std::make_unique<Director>(cluster, scene, *show);
    }
    std::string apply(const std::string& line, uint64_t next) {
        return director->apply(parse_control_line(line), next);
    }
    glm::dvec3 body_pos(const Snapshot& s, const std::string& name) {
        return s.bodies[scene.find(name)->id].position_m;
    }

    ClusterConfig cluster;
    SceneConfig scene;
    std::unique_ptr<ShowScript> show;
    std::unique_ptr<Director> director;
    NavSample no_device;
};

}  // namespace

TEST(ControlCommand, ParsesTheLanguage) {
    auto c = parse_control_line("goto Moon");
    EXPECT_EQ(c.verb, ControlVerb::Goto);
    EXPECT_EQ(c.body, "Moon");
    EXPECT_FALSE(c.seconds);
    c = parse_control_line("  GOTO earth 2.5 ");
    EXPECT_EQ(c.verb, ControlVerb::Goto);
    EXPECT_DOUBLE_EQ(*c.seconds, 2.5);
    EXPECT_FALSE(c.height_m);
    c = parse_control_line("goto Earth 3 height 1500");
    EXPECT_DOUBLE_EQ(*c.seconds, 3.0);
    EXPECT_DOUBLE_EQ(*c.height_m, 1500.0);
    c = parse_control_line("goto Earth HEIGHT 20");
    EXPECT_FALSE(c.seconds);
    EXPECT_DOUBLE_EQ(*c.height_m, 20.0);
    c = parse_control_line("time rate -3600");
    EXPECT_EQ(c.verb, ControlVerb::TimeRate);
    EXPECT_DOUBLE_EQ(c.rate, -3600.0);
    c = parse_control_line("time set 2024-04-08T18:17:00Z");
    EXPECT_EQ(c.verb, ControlVerb::TimeSet);
    EXPECT_DOUBLE_EQ(c.sim_time_s, utc_iso_to_j2000_seconds("2024-04-08T18:17:00Z"));
    c = parse_control_line("set twinkle Forced");
    EXPECT_EQ(c.setting, "twinkle");
    EXPECT_EQ(c.value, "forced");
    EXPECT_NE(parse_error("set twinkle sparkle").find("not one of on, off, forced, show"), std::string::npos)
        << parse_error("set twinkle sparkle");
    c = parse_control_line("set bortle 8");  // a class is a zenith brightness
    EXPECT_EQ(c.setting, "sky_brightness");
    EXPECT_DOUBLE_EQ(*c.number, bortle_zenith_mag_arcsec2(8));
    EXPECT_DOUBLE_EQ(*parse_control_line("set sky_brightness 21.5").number, 21.5);
    EXPECT_FALSE(parse_control_line("set bortle show").number);
    EXPECT_NE(parse_error("set bortle 10").find("class 1..9"), std::string::npos) << parse_error("set bortle 10");
    EXPECT_NE(parse_error("set bortle 2.5").find("class 1..9"), std::string::npos);
    EXPECT_NE(parse_error("set sky_brightness 30").find("14..24"), std::string::npos);
    EXPECT_EQ(parse_control_line("play").show_file, "");
    EXPECT_EQ(parse_control_line("play shows/x.json").show_file, "shows/x.json");
    EXPECT_EQ(parse_control_line("pause").verb, ControlVerb::Pause);
    EXPECT_EQ(parse_control_line("quit\r").verb, ControlVerb::Quit);
    c = parse_control_line("mode walk Earth");
    EXPECT_EQ(c.nav_mode, "walk");
    EXPECT_EQ(c.body, "Earth");
    c = parse_control_line("set shadow_mode Illustrative");
    EXPECT_EQ(c.setting, "shadow_mode");
    EXPECT_EQ(c.value, "illustrative");
}

TEST(ControlCommand, ErrorsSayWhatWasWrong) {
    EXPECT_NE(parse_error("").find("empty line"), std::string::npos);
    EXPECT_NE(parse_error("fly me to the moon").find("unknown command \"fly\""), std::string::npos);
    EXPECT_NE(parse_error("time rate fast").find("\"fast\" is not a number"), std::string::npos);
    EXPECT_NE(parse_error("time rate 1e300").find("beyond"), std::string::npos);
    EXPECT_NE(parse_error("time rate nan").find("not a number"), std::string::npos);
    EXPECT_NE(parse_error("time set yesterday").find("yesterday"), std::string::npos);
    EXPECT_NE(parse_error("time warp 3").find("\"warp\""), std::string::npos);
    EXPECT_NE(parse_error("goto").find("usage: goto"), std::string::npos);
    EXPECT_NE(parse_error("goto moon -1").find("0..600"), std::string::npos);
    EXPECT_NE(parse_error("goto moon 3 high 500").find("\"high\""), std::string::npos);
    EXPECT_NE(parse_error("goto moon height").find("\"height\""), std::string::npos);
    EXPECT_NE(parse_error("goto moon height 1").find("2 .. 1e9 m"), std::string::npos);
    EXPECT_NE(parse_error("goto moon height tall").find("\"tall\""), std::string::npos);
    EXPECT_NE(parse_error("mode swim").find("\"swim\""), std::string::npos);
    EXPECT_NE(parse_error("set shadow_mode sharp").find("\"sharp\""), std::string::npos);
    EXPECT_NE(parse_error("set exposure 0").find("[1e-12, 1e6]"), std::string::npos);
    EXPECT_NE(parse_error("set exposure 1e-50").find("[1e-12, 1e6]"), std::string::npos);  // not a float
    EXPECT_NE(parse_error("set gamma 2").find("\"gamma\""), std::string::npos);
    EXPECT_NE(parse_error("pause now").find("usage"), std::string::npos);
    EXPECT_NE(parse_error(std::string(2000, 'a')).find("too long"), std::string::npos);
    EXPECT_NE(parse_error(std::string("goto \x01moon")).find("control character"), std::string::npos);
}

TEST(ControlServer, LinesFromSeveralClientsAndRepliesToEach) {
    const std::string dir = test::scratch_dir("control_server");
    const std::string path = dir + "/control.sock";
    ControlServer server(path);
    ControlClient a(path), b(path);
    ASSERT_TRUE(a.connected());
    ASSERT_TRUE(b.connected());
    ASSERT_TRUE(a.send_raw("goto moon\ntime ra"));
    ASSERT_TRUE(b.send_raw("pause\r\n"));
    ASSERT_TRUE(a.send_raw("te 10\n"));  // a line split over two writes
    auto reqs = take_n(server, 3);
    ASSERT_EQ(reqs.size(), 3u);
    std::vector<std::string> lines;
    for (const auto& r : reqs) lines.push_back(r.line);
    EXPECT_NE(std::find(lines.begin(), lines.end(), "goto moon"), lines.end());
    EXPECT_NE(std::find(lines.begin(), lines.end(), "time rate 10"), lines.end());
    EXPECT_NE(std::find(lines.begin(), lines.end(), "pause"), lines.end());
    for (const auto& r : reqs) server.reply(r.client, "echo " + r.line);
    const std::string a1 = a.read_line(), a2 = a.read_line(), b1 = b.read_line();
    EXPECT_EQ(a1, "echo goto moon");
    EXPECT_EQ(a2, "echo time rate 10");
    EXPECT_EQ(b1, "echo pause");
    // An over-long line is refused as one line (and answered), not split into commands.
    ASSERT_TRUE(a.send_raw(std::string(5000, 'x') + "\nstatus\n"));
    reqs = take_n(server, 2);
    ASSERT_EQ(reqs.size(), 2u);
    EXPECT_GT(reqs[0].line.size(), 1024u);
    EXPECT_EQ(reqs[1].line, "status");
    EXPECT_EQ(server.lines_refused(), 1u);
}

TEST(ControlServer, StaleSocketIsReplacedLiveOneIsAnError) {
    const std::string dir = test::scratch_dir("control_stale");
    const std::string path = dir + "/control.sock";
    {
        // A socket file nobody listens on (a master that died).
        int fd = socket(AF_UNIX, SOCK_STREAM, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
        ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
        close(fd);
    }
    auto first = std::make_unique<ControlServer>(path);
    try {
        ControlServer second(path);
        FAIL() << "a second master took over a live control socket";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("another process is listening"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    }
    test::write_text(dir + "/plain", "x");
    EXPECT_THROW(ControlServer(dir + "/plain"), std::runtime_error);
    first.reset();
    EXPECT_FALSE(std::filesystem::exists(path));  // removed on exit
}

TEST_F(DirectorFixture, QuietDirectorIsTheShow) {
    // Without commands or input every frame is exactly the show's (what tests recompute).
    for (uint64_t f : {0, 1, 2, 57, 300}) {
        DirectedFrame d = director->frame(f, no_device);
        finish_frame_snapshot(d.snapshot, d.settings, cluster, scene, f, director->frame_interval_s(), nullptr,
                              nullptr);
        EXPECT_EQ(d.snapshot, make_frame_snapshot(cluster, scene, *show, f)) << "frame " << f;
    }
}

TEST_F(DirectorFixture, TimeRateAndSetAndPause) {
    const double dt = show->frame_interval_s();
    const double t10 = director->frame(10, no_device).snapshot.sim_time_s;
    EXPECT_NE(apply("time rate 3600", 11).find("time rate 3600"), std::string::npos);
    EXPECT_TRUE(director->live());
    // The show ran at 3 h of sim time per 20 s; from frame 11 on the clock runs at 3600 x.
    const double show_rate = 3600.0 / 20.0;
    const double t11 = director->frame(11, no_device).snapshot.sim_time_s;
    EXPECT_NEAR(t11 - t10, show_rate * dt, 1e-6);
    for (uint64_t f = 12; f < 20; ++f) {
        const double t = director->frame(f, no_device).snapshot.sim_time_s;
        EXPECT_NEAR(t - t11, 3600.0 * dt * static_cast<double>(f - 11), 1e-6);
    }
    // The camera stays with the Earth (free fly, anchored) while time runs fast.
    const Snapshot s19 = director->frame(20, no_device).snapshot;
    const Snapshot s11 = show->evaluate(11 * dt, scene);  // where the show handed over
    EXPECT_NEAR(glm::length((s19.camera_position_m - body_pos(s19, "earth")) -
                            (s11.camera_position_m - body_pos(s11, "earth"))),
                0.0, 1e-3);
    apply("time set 2024-04-08T18:17:00Z", 21);
    const double t_set = utc_iso_to_j2000_seconds("2024-04-08T18:17:00Z");
    EXPECT_DOUBLE_EQ(director->frame(21, no_device).snapshot.sim_time_s, t_set);
    EXPECT_NEAR(director->frame(22, no_device).snapshot.sim_time_s, t_set + 3600.0 * dt, 1e-6);
    apply("pause", 23);
    const double tp = director->frame(23, no_device).snapshot.sim_time_s;
    EXPECT_EQ(director->frame(30, no_device).snapshot.sim_time_s, tp);
    apply("resume", 31);
    EXPECT_NEAR(director->frame(32, no_device).snapshot.sim_time_s, tp + 3600.0 * dt, 1e-6);
    apply("time rate -60", 33);
    EXPECT_NEAR(director->frame(35, no_device).snapshot.sim_time_s - director->frame(34, no_device).snapshot.sim_time_s,
                -60.0 * dt, 1e-6);
    const auto st = director->status(36);
    EXPECT_EQ(st["mode"], "live");
    EXPECT_DOUBLE_EQ(st["rate"].get<double>(), -60.0);
}

TEST_F(DirectorFixture, GotoFliesToTheBodyAndOrbitsIt) {
    director->frame(0, no_device);
    EXPECT_THROW(apply("goto Pluto", 1), ControlError);
    EXPECT_FALSE(director->live());  // a refused command changes nothing
    apply("goto Moon 2", 1);         // 2 s = 50 frames of 0.04 s
    const double moon_r = scene.find("moon")->radius_m;
    double last_d = 1e300;
    for (uint64_t f = 1; f <= 51; ++f) {
        const Snapshot s = director->frame(f, no_device).snapshot;
        const double d = glm::length(s.camera_position_m - body_pos(s, "moon"));
        EXPECT_LE(d, last_d * (1 + 1e-12)) << "frame " << f;
        last_d = d;
    }
    // Arrived: 4 radii from the Moon's centre, looking at it, and staying there.
    for (uint64_t f = 52; f < 60; ++f) {
        const Snapshot s = director->frame(f, no_device).snapshot;
        const glm::dvec3 rel = body_pos(s, "moon") - s.camera_position_m;
        EXPECT_NEAR(glm::length(rel), 4.0 * moon_r, 1e-3);
        const glm::dvec3 fwd = glm::mat3_cast(s.camera_orientation) * glm::dvec3(0, 0, -1);
        EXPECT_NEAR(glm::dot(fwd, glm::normalize(rel)), 1.0, 1e-9);
    }
    EXPECT_EQ(director->status(60)["navigation"]["anchor"], "moon");
}

TEST_F(DirectorFixture, DeviceTakesOverAndUnplugStopsTheCamera) {
    const Snapshot s0 = director->frame(0, no_device).snapshot;
    NavSample dev;
    dev.connected = true;
    dev.device = "test";
    dev.axes.forward = 0.02;  // inside the dead zone: the show keeps playing
    for (uint64_t f = 1; f < 5; ++f) {
        DirectedFrame d = director->frame(f, dev);
        EXPECT_FALSE(director->live());
        EXPECT_FALSE(d.input_used);
        EXPECT_EQ(d.snapshot, show->evaluate(static_cast<double>(f) * show->frame_interval_s(), scene));
    }
    dev.axes.forward = 1.0;
    dev.report_ns = 12345;
    dev.reports = 1;  // a fresh report
    DirectedFrame d5 = director->frame(5, dev);
    EXPECT_TRUE(director->live());
    EXPECT_TRUE(d5.input_used);
    EXPECT_EQ(d5.input_report_ns, 12345u);
    glm::dvec3 prev = d5.snapshot.camera_position_m - body_pos(d5.snapshot, "earth");
    double moved = 0.0;
    for (uint64_t f = 6; f < 20; ++f) {
        const Snapshot s = director->frame(f, dev).snapshot;
        const glm::dvec3 rel = s.camera_position_m - body_pos(s, "earth");
        moved += glm::length(rel - prev);
        prev = rel;
    }
    EXPECT_GT(moved, 1000.0);  // flying toward the Earth at a fraction of the altitude per second
    // Unplugged: the next frame does not move (no smoothing tail), nor any later one.
    dev.connected = false;
    dev.axes = {};
    for (uint64_t f = 20; f < 30; ++f) {
        const Snapshot s = director->frame(f, dev).snapshot;
        const glm::dvec3 rel = s.camera_position_m - body_pos(s, "earth");
        EXPECT_NEAR(glm::length(rel - prev), 0.0, 1e-6) << "frame " << f;
        prev = rel;
    }
    (void)s0;
}

TEST_F(DirectorFixture, PlayStopSettingsAndQuit) {
    director->frame(0, no_device);
    apply("stop", 1);
    EXPECT_TRUE(director->live());
    director->frame(1, no_device);
    apply("set shadow_mode illustrative", 2);
    EXPECT_EQ(shadow_mode_of(director->frame(2, no_device).snapshot.settings.flags), ShadowMode::Illustrative);
    apply("set twinkle forced", 2);
    EXPECT_EQ(twinkle_mode_of(director->frame(2, no_device).snapshot.settings.flags), TwinkleMode::Forced);
    apply("set twinkle show", 2);
    EXPECT_EQ(twinkle_mode_of(director->frame(2, no_device).snapshot.settings.flags), scene.stars.twinkle);
    apply("set exposure 3", 3);
    apply("set bortle 8", 3);
    DirectedFrame d = director->frame(3, no_device);
    finish_frame_snapshot(d.snapshot, d.settings, cluster, scene, 3, director->frame_interval_s(), nullptr, nullptr);
    EXPECT_FLOAT_EQ(d.snapshot.settings.exposure, 3.0f);
    EXPECT_FLOAT_EQ(d.snapshot.settings.night_sky_cd_m2, static_cast<float>(sky_brightness_cd_m2(18.0)));
    apply("show grid equatorial", 3);
    EXPECT_TRUE(*director->frame(3, no_device).settings.overlays[static_cast<size_t>(OverlayKind::GridEquatorial)]);
    apply("hide grid equatorial", 3);
    EXPECT_FALSE(*director->frame(3, no_device).settings.overlays[static_cast<size_t>(OverlayKind::GridEquatorial)]);
    apply("show overlays show", 3);
    EXPECT_FALSE(director->frame(3, no_device).settings.overlays[static_cast<size_t>(OverlayKind::GridEquatorial)]);
    apply("set bortle show", 3);
    d = director->frame(3, no_device);
    finish_frame_snapshot(d.snapshot, d.settings, cluster, scene, 3, director->frame_interval_s(), nullptr, nullptr);
    EXPECT_FLOAT_EQ(d.snapshot.settings.night_sky_cd_m2, 0.0f);  // the scene has none
    apply("set exposure auto", 4);
    d = director->frame(4, no_device);
    finish_frame_snapshot(d.snapshot, d.settings, cluster, scene, 4, director->frame_interval_s(), nullptr, nullptr);
    EXPECT_FLOAT_EQ(d.snapshot.settings.exposure, static_cast<float>(cluster.output.exposure));
    // Live clock changes do not move the show's place: play resumes the show where it was left
    // (show time 1 frame), now at frame 5.
    apply("time rate 10", 4);
    director->frame(4, no_device);
    apply("play", 5);
    EXPECT_FALSE(director->live());
    EXPECT_EQ(director->frame(5, no_device).snapshot.sim_time_s,
              show->evaluate(1 * show->frame_interval_s(), scene).sim_time_s);
    // play another show: from its start.
    const std::string other = test::source_path("configs/shows/eclipse-2006-ground.json");
    EXPECT_NE(apply("play " + other, 6).find("eclipse-2006-ground"), std::string::npos);
    EXPECT_DOUBLE_EQ(director->frame(6, no_device).snapshot.sim_time_s,
                     utc_iso_to_j2000_seconds("2006-03-29T10:00:25Z"));
    EXPECT_THROW(apply("play /nonexistent/show.json", 7), ControlError);
    EXPECT_FALSE(director->quit_requested());
    apply("quit", 8);
    EXPECT_TRUE(director->quit_requested());
}

TEST(ControlServer, InputThatEndsIsStillAnswered) {
    // A client that sends its commands and half-closes (printf ... | nc -N) gets its replies.
    const std::string dir = test::scratch_dir("control_eof");
    const std::string path = dir + "/control.sock";
    ControlServer server(path);
    ControlClient a(path);
    ASSERT_TRUE(a.connected());
    ASSERT_TRUE(a.send_raw("status\nquit\n"));
    // Half-close our side: the server sees the end of input before it answers.
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_EQ(shutdown(a.fd(), SHUT_WR), 0);
    auto reqs = take_n(server, 2);
    ASSERT_EQ(reqs.size(), 2u);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // the reader has seen the end
    for (const auto& r : reqs) server.reply(r.client, "ok " + r.line);
    EXPECT_EQ(a.read_line(), "ok status");
    EXPECT_EQ(a.read_line(), "ok quit");
    EXPECT_EQ(a.read_line(), "(no reply)");  // then the server closed the connection
}

TEST_F(DirectorFixture, ButtonsCycleTheModeAndPauseOncePerPress) {
    // Defaults: button 0 = next navigation mode, button 1 = pause / resume.
    director->frame(0, no_device);
    NavSample dev;
    dev.connected = true;
    dev.buttons = 1u;  // press button 0 and hold it for three frames
    for (uint64_t f = 1; f <= 3; ++f) director->frame(f, dev);
    EXPECT_TRUE(director->live());
    EXPECT_EQ(director->status(4)["navigation"]["mode"], "orbit");  // once, not once per frame
    dev.buttons = 0u;
    director->frame(4, dev);
    dev.buttons = 1u;
    director->frame(5, dev);
    EXPECT_EQ(director->status(6)["navigation"]["mode"], "free_fly");
    dev.buttons = 0u;
    director->frame(6, dev);
    dev.buttons = 1u;
    director->frame(7, dev);
    EXPECT_EQ(director->status(8)["navigation"]["mode"], "surface_walk");
    // Button 1: pause, then resume on the next press.
    dev.buttons = 2u;
    const double t8 = director->frame(8, dev).snapshot.sim_time_s;
    EXPECT_EQ(director->frame(9, dev).snapshot.sim_time_s, t8);
    EXPECT_EQ(director->frame(12, dev).snapshot.sim_time_s, t8);
    dev.buttons = 0u;
    director->frame(13, dev);
    dev.buttons = 2u;
    EXPECT_EQ(director->frame(14, dev).snapshot.sim_time_s, t8);  // runs again from here
    EXPECT_GT(director->frame(15, dev).snapshot.sim_time_s, t8);
    // Unplugging with a button held, and plugging in again without it, is not a press.
    dev.connected = false;
    director->frame(16, dev);
    dev.connected = true;
    dev.buttons = 0u;
    director->frame(17, dev);
    EXPECT_EQ(director->status(18)["paused"], false);
}

// A loopback dome driven through the master's control socket: goto, time rate, a settings
// switch, the cupola-control tool, the head (the presenter's, a DTrack2 tracker's over UDP, then
// lost) and quit, checked in the master's snapshots (events file) and
// in every channel's frames (the snapshot hash each frame file records).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>

#include "config/cluster_config.hpp"
#include "eclipse/shadow_casters.hpp"
#include "image/frame_image.hpp"
#include "net/udp_socket.hpp"
#include "scene/ephemeris.hpp"
#include "support/cluster_fixture.hpp"
#include "support/control_client.hpp"
#include "support/loopback_run.hpp"
#include "support/test_support.hpp"
#include "util/child_process.hpp"

using namespace cupola;

namespace {

// "... frame 123" -> 123
uint64_t frame_in(const std::string& reply) {
    std::smatch m;
    if (!std::regex_search(reply, m, std::regex("frame (\\d+)"))) return 0;
    return std::stoull(m[1]);
}

std::map<uint64_t, nlohmann::json> frames_of(const std::string& events_file) {
    std::map<uint64_t, nlohmann::json> out;
    for (const auto& e : test::read_events(events_file))
        if (e.is_object() && e.value("event", "") == "frame") out[e.at("frame").get<uint64_t>()] = e;
    return out;
}

glm::dvec3 vec(const nlohmann::json& a) { return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; }

nlohmann::json last_event(const std::string& events_file, const std::string& kind) {
    nlohmann::json last;
    for (const auto& e : test::read_events(events_file))
        if (e.is_object() && e.value("event", "") == kind) last = e;
    return last;
}

}  // namespace

TEST(ControlLoopback, GotoTimeRateSettingsAndQuitReachEveryChannel) {
    const std::string dir = test::scratch_dir("control_loopback");
    // The head follows a DTrack2 tracker on 127.0.0.1:47968 (given up 0.5 s after its last datagram).
    const nlohmann::json tracking = {
        {"source", "dtrack"}, {"address", "127.0.0.1"}, {"port", 47968}, {"fresh_s", 0.5}, {"timeout_s", 0.5}};
    const std::string config = test::write_test_cluster(
        dir, 47960, 48, 48,
        {{"input", {{"usb", false}}}, {"room", {{"eye_m", {0.0, 1.6, 0.0}}, {"tracking", tracking}}}});
    const ClusterConfig cfg = load_cluster_config(config);
    const SceneConfig scene = load_scene_config(cfg.scene_file);
    const std::string sock = dir + "/control.sock", out = dir + "/out", events = out + "/logs/events.jsonl";
    ChildProcess loopback({test::bin_path("cupola-loopback"), "--config", config, "--out", out, "--control", sock,
                           "--frames", "5000", "--timeout", "280"},
                          dir + "/loopback.log", {"DISPLAY", "WAYLAND_DISPLAY", "SPDLOG_LEVEL"});
    ASSERT_TRUE(test::wait_until([&] { return std::filesystem::exists(sock); }, std::chrono::seconds(60)))
        << test::read_text(dir + "/loopback.log");
    test::ControlClient console(sock, 60);
    ASSERT_TRUE(console.connected());
    auto frames_rendered = [&](uint64_t n) {
        return test::wait_until([&] { return frames_of(events).size() >= n; }, std::chrono::seconds(120));
    };
    ASSERT_TRUE(frames_rendered(3)) << test::read_text(out + "/logs/master.log");

    const std::string status = console.command("status");
    ASSERT_EQ(status.rfind("ok {", 0), 0u) << status;
    EXPECT_EQ(nlohmann::json::parse(status.substr(3))["mode"], "show");

    // goto: a 1 s flight (25 frames of 0.04 s), then orbiting the Moon at 4 radii.
    const std::string go = console.command("goto Moon 1");
    ASSERT_EQ(go.rfind("ok goto moon", 0), 0u) << go;
    const uint64_t f_goto = frame_in(go);
    ASSERT_TRUE(frames_rendered(f_goto + 30));
    {
        const auto fr = frames_of(events);
        const double moon_r = scene.find("moon")->radius_m;
        for (uint64_t f = f_goto + 26; f < f_goto + 30; ++f) {
            const auto& e = fr.at(f);
            EXPECT_EQ(e["mode"], "live");
            const glm::dvec3 moon = body_state(*scene.find("moon"), e["sim_time_s"].get<double>()).position_m;
            EXPECT_NEAR(glm::length(vec(e["camera_m"]) - moon), 4.0 * moon_r, 1.0) << "frame " << f;
        }
        EXPECT_EQ(fr.at(f_goto - 1)["mode"], "show");  // the command took effect exactly at its frame
    }

    // time rate: from its frame on, each frame advances the clock by 3600 x 0.04 s.
    const std::string rate = console.command("time rate 3600");
    ASSERT_EQ(rate.rfind("ok time rate 3600", 0), 0u) << rate;
    const uint64_t f_rate = frame_in(rate);
    // A settings switch through the tool (a real client process), and a refused command.
    const auto [tool_rc, tool_out] =
        test::run_shell(test::bin_path("cupola-control") + " " + sock + " set shadow_mode illustrative");
    EXPECT_EQ(tool_rc, 0) << tool_out;
    const uint64_t f_shadow = frame_in(tool_out);
    const auto [bad_rc, bad_out] = test::run_shell(test::bin_path("cupola-control") + " " + sock + " goto Vulcan");
    EXPECT_EQ(bad_rc, 1);
    EXPECT_NE(bad_out.find("error no body named \"Vulcan\""), std::string::npos) << bad_out;
    ASSERT_TRUE(frames_rendered(std::max(f_rate, f_shadow) + 5));
    {
        const auto fr = frames_of(events);
        for (uint64_t f = f_rate + 1; f < f_rate + 5; ++f)
            EXPECT_NEAR(fr.at(f)["sim_time_s"].get<double>() - fr.at(f - 1)["sim_time_s"].get<double>(), 144.0, 1e-6);
        EXPECT_EQ(shadow_mode_of(fr.at(f_shadow)["flags"].get<uint32_t>()), ShadowMode::Illustrative);
        EXPECT_NE(shadow_mode_of(fr.at(f_shadow - 1)["flags"].get<uint32_t>()), ShadowMode::Illustrative);
    }

    // The head: the presenter's pose from its frame on, then the tracker's, then the default eye
    // once the tracker has been silent for its timeout.
    const std::string head = console.command("head 0.3 1.5 -0.2");
    ASSERT_EQ(head.rfind("ok head at (0.3, 1.5, -0.2) m", 0), 0u) << head;
    const uint64_t f_head = frame_in(head);
    ASSERT_TRUE(frames_rendered(f_head + 2));
    EXPECT_EQ(frames_of(events).at(f_head)["head_source"], "control");
    EXPECT_LT(glm::length(vec(frames_of(events).at(f_head)["head_m"]) - glm::dvec3(0.3, 1.5, -0.2)), 1e-12);
    EXPECT_EQ(frames_of(events).at(f_head - 1)["head_source"], "default");
    const uint64_t f_release = frame_in(console.command("head release"));
    UdpSocket tracker;
    const std::string datagram = "fr 1\r\n6d 1 [0 1.000][-400 1500 250 0 0 0][1 0 0 0 1 0 0 0 1]\r\n";
    const auto tracked = [&] {
        tracker.send_to(make_address("127.0.0.1", 47968), reinterpret_cast<const uint8_t*>(datagram.data()),
                        datagram.size());
        for (const auto& [f, e] : frames_of(events))
            if (f > f_release && e["head_source"] == "tracked") return true;
        return false;
    };
    ASSERT_TRUE(test::wait_until(tracked, std::chrono::seconds(60))) << test::read_text(out + "/logs/master.log");
    uint64_t f_tracked = 0;
    for (const auto& [f, e] : frames_of(events))
        if (f > f_release && e["head_source"] == "tracked" && !f_tracked) f_tracked = f;
    const nlohmann::json te = frames_of(events).at(f_tracked);
    EXPECT_LT(glm::length(vec(te["head_m"]) - glm::dvec3(-0.4, 1.5, 0.25)), 1e-12) << "millimetres to metres";
    EXPECT_GE(te["head_latency_ms"].get<double>(), 0.0);
    const auto lost = [&] {
        const auto fr = frames_of(events);
        return fr.rbegin()->second["head_source"] == "default";
    };
    ASSERT_TRUE(test::wait_until(lost, std::chrono::seconds(60)));
    EXPECT_LT(glm::length(vec(frames_of(events).rbegin()->second["head_m"]) - glm::dvec3(0.0, 1.6, 0.0)), 1e-12);

    const std::string quit = console.command("quit");
    ASSERT_EQ(quit.rfind("ok quit before frame", 0), 0u) << quit;
    const uint64_t f_quit = frame_in(quit);
    const auto rc = loopback.wait_for(std::chrono::seconds(200));
    ASSERT_TRUE(rc.has_value()) << "the loopback did not end after quit";
    EXPECT_EQ(*rc, 0) << test::read_text(dir + "/loopback.log");

    // Every channel wrote every frame up to the quit, each from the snapshot the master sent.
    const auto fr = frames_of(events);
    ASSERT_EQ(fr.size(), f_quit);
    EXPECT_EQ(fr.rbegin()->first, f_quit - 1);
    for (uint64_t f = 0; f < f_quit; ++f) {
        for (const auto& ch : cfg.channels) {
            FrameMetadata meta;
            read_image(out + "/" + ch.name + "/" + frame_file_name(f, "png"), &meta);
            EXPECT_EQ(meta.snapshot_hash, fr.at(f)["hash"].get<std::string>()) << ch.name << " frame " << f;
        }
    }
    EXPECT_TRUE(std::filesystem::exists(out + "/dome/" + frame_file_name(f_quit - 1, "png")));
    EXPECT_FALSE(std::filesystem::exists(sock));  // the master removed its socket
    // The tracker's loss is counted in the master's end event.
    const nlohmann::json end = last_event(events, "end");
    EXPECT_GE(end["stats"]["head"]["losses"].get<int>(), 1) << end.dump();
    EXPECT_GE(end["stats"]["head"]["samples"].get<int>(), 1);
}

// Fault: a slave killed mid-run is timed out by the master while the other channels keep
// rendering; restarted, it rejoins and renders the current frame. Real processes throughout.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "config/cluster_config.hpp"
#include "image/frame_image.hpp"
#include "support/cluster_fixture.hpp"
#include "support/loopback_run.hpp"
#include "util/child_process.hpp"

using namespace cupola;
namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

using test::read_events;
using test::wait_until;

}  // namespace

TEST(Fault, KilledSlaveIsDroppedOthersGoOnRestartedSlaveRejoinsAtTheCurrentFrame) {
    const std::string dir = test::scratch_dir("fault");
    // The master runs until the test has seen the victim rejoin and render a few frames, then is
    // stopped (SIGTERM: it finishes the frame, tells the slaves to quit and exits 0): however long
    // a restart takes under load, the rejoin falls inside the run. max_frames only bounds it.
    const int max_frames = 4000;
    const std::string config =
        test::write_test_cluster(dir, 47840, 48, 48,
                                 {{"frame_rate_hz", 8},
                                  {"output", {{"formats", {"png"}}}},
                                  {"network", {{"channel_timeout_ms", 2500}, {"resend_interval_ms", 100}}}});
    const ClusterConfig cfg = load_cluster_config(config);
    const std::vector<std::string> headless = {"DISPLAY", "WAYLAND_DISPLAY"};
    auto start_slave = [&](const ChannelConfig& ch) {
        return ChildProcess({test::bin_path("cupola-slave"), "--config", config, "--channel", ch.name, "--out",
                             dir + "/" + ch.name, "--idle-timeout", "60"},
                            dir + "/" + ch.name + ".log", headless);
    };
    std::vector<ChildProcess> slaves;
    for (const auto& ch : cfg.channels) slaves.push_back(start_slave(ch));
    const std::string events_file = dir + "/events.jsonl";
    ChildProcess master({test::bin_path("cupola-master"), "--config", config, "--frames", std::to_string(max_frames),
                         "--events", events_file},
                        dir + "/master.log", headless);

    const ChannelConfig& victim = cfg.channels[2];
    const std::string victim_dir = dir + "/" + victim.name;
    ASSERT_TRUE(wait_until([&] { return fs::exists(victim_dir + "/" + frame_file_name(8, "png")); }, 120s))
        << "the victim never reached frame 8";
    slaves[2].kill(SIGKILL);
    ASSERT_TRUE(slaves[2].wait_for(5s).has_value());

    // The master drops it after the timeout; the others keep rendering.
    auto dropped = [&] {
        for (const auto& e : read_events(events_file))
            if (e.value("event", "") == "channel_dropped" && e.value("channel", -1) == victim.id) return true;
        return false;
    };
    ASSERT_TRUE(wait_until(dropped, 60s)) << test::read_text(dir + "/master.log");
    // Let a few frames pass without it.
    std::this_thread::sleep_for(800ms);
    slaves[2] = start_slave(victim);
    const int frames_after_rejoin = 8;
    auto rejoined_and_rendering = [&] {
        bool joined = false, dropped_seen = false;
        int after = 0;
        for (const auto& e : read_events(events_file)) {
            const std::string kind = e.value("event", "");
            if (kind == "channel_dropped" && e.value("channel", -1) == victim.id) dropped_seen = true;
            if (kind == "channel_joined" && e.value("channel", -1) == victim.id && dropped_seen) joined = true;
            if (kind == "frame" && joined) ++after;
        }
        return after >= frames_after_rejoin;
    };
    ASSERT_TRUE(wait_until(rejoined_and_rendering, 240s)) << test::read_text(dir + "/master.log");
    master.kill(SIGTERM);

    auto mrc = master.wait_for(60s);
    ASSERT_TRUE(mrc.has_value()) << "master did not finish";
    EXPECT_EQ(*mrc, 0) << test::read_text(dir + "/master.log");
    for (auto& s : slaves) {
        auto rc = s.wait_for(30s);
        ASSERT_TRUE(rc.has_value()) << "a slave did not quit";
        EXPECT_EQ(*rc, 0);
    }

    // Events: dropped at frame D, rejoined at frame J > D, then reported until the end.
    uint64_t drop_frame = 0, join_frame = 0;
    bool seen_drop = false, seen_rejoin = false;
    std::vector<nlohmann::json> frame_events;
    for (const auto& e : read_events(events_file)) {
        const std::string kind = e.value("event", "");
        if (kind == "channel_dropped" && e["channel"] == victim.id && !seen_drop) {
            seen_drop = true;
            drop_frame = e["frame"];
        }
        if (kind == "channel_joined" && e["channel"] == victim.id && seen_drop && !seen_rejoin) {
            seen_rejoin = true;
            join_frame = e["frame"];
        }
        if (kind == "frame") frame_events.push_back(e);
    }
    ASSERT_TRUE(seen_drop);
    ASSERT_TRUE(seen_rejoin) << test::read_text(dir + "/master.log");
    EXPECT_GT(join_frame, drop_frame);
    // Every frame 0..N-1 was reported once, in order, and the victim rendered some after its rejoin.
    const int frames = static_cast<int>(frame_events.size());
    for (int f = 0; f < frames; ++f) ASSERT_EQ(frame_events[static_cast<size_t>(f)]["frame"].get<int>(), f);
    EXPECT_GE(frames, static_cast<int>(join_frame) + frames_after_rejoin);
    EXPECT_LT(frames, max_frames);

    // The other channels rendered every frame, including while the victim was gone.
    for (const auto& ch : cfg.channels) {
        if (ch.id == victim.id) continue;
        for (int f = 0; f < frames; ++f)
            EXPECT_TRUE(fs::exists(dir + "/" + ch.name + "/" + frame_file_name(f, "png"))) << ch.name << " " << f;
    }
    // Frames between the drop and the rejoin went on without the victim...
    int without = 0;
    for (const auto& e : frame_events) {
        const uint64_t f = e["frame"];
        if (f > drop_frame && f < join_frame) {
            EXPECT_FALSE(e["channels"].contains(std::to_string(victim.id))) << f;
            EXPECT_EQ(e["channels"].size(), cfg.channels.size() - 1) << f;
            ++without;
        }
    }
    EXPECT_GE(without, 1);
    // ...and the restarted victim rendered the current frame at its rejoin, with the same snapshot
    // as everyone else, and every frame after it.
    FrameMetadata vm, om;
    read_image(victim_dir + "/" + frame_file_name(join_frame, "png"), &vm);
    read_image(dir + "/" + cfg.channels[0].name + "/" + frame_file_name(join_frame, "png"), &om);
    EXPECT_EQ(vm.snapshot_hash, om.snapshot_hash);
    EXPECT_EQ(vm.frame, join_frame);
    for (int f = static_cast<int>(join_frame); f < frames; ++f)
        EXPECT_TRUE(fs::exists(victim_dir + "/" + frame_file_name(f, "png"))) << f;
    for (const auto& e : frame_events) {
        if (e["frame"].get<uint64_t>() > join_frame) {
            EXPECT_TRUE(e["channels"].contains(std::to_string(victim.id))) << e.dump();
        }
    }
}

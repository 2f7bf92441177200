// The swap lock (docs/SWAP_LOCK.md) with real processes over real UDP: a master and four slaves,
// each slave writing one line per frame shown (--present-log: ready_ns, present_ns, both
// CLOCK_MONOTONIC, one clock on one host). Orderings are asserted, not durations, except the
// bounded delay a killed slave may cost, which has generous slack.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <deque>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config/cluster_config.hpp"
#include "present_skew.hpp"
#include "support/cluster_fixture.hpp"
#include "support/loopback_run.hpp"
#include "util/child_process.hpp"

using namespace cupola;
namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

struct Shown {
    uint64_t ready_ns = 0;
    uint64_t present_ns = 0;
    std::string cause;
};
using PresentLog = std::map<uint64_t, Shown>;  // by frame

// One slave's --present-log; frames must come in increasing order, each shown once, never before
// the slave itself was ready.
PresentLog read_present_log(const std::string& path) {
    PresentLog log;
    std::optional<uint64_t> last;
    for (const nlohmann::json& e : test::read_events(path)) {
        const uint64_t f = e.at("frame");
        EXPECT_TRUE(!last || f > *last) << path << ": frame " << f << " shown after " << *last;
        last = f;
        Shown s{e.at("ready_ns"), e.at("present_ns"), e.at("cause")};
        EXPECT_GE(s.present_ns, s.ready_ns) << path << ": frame " << f << " shown before it was ready";
        log[f] = s;
    }
    return log;
}

// A master and one slave per channel of a 4-channel config at 32×32 in `dir`.
struct SwapLockCluster {
    SwapLockCluster(const std::string& dir, int port_base, int frames, const nlohmann::json& network)
        : dir(dir),
          config(test::write_test_cluster(
              dir, port_base, 32, 32,
              {{"frame_rate_hz", 0}, {"output", {{"formats", {"png"}}}}, {"network", network}})),
          cfg(load_cluster_config(config)) {
        for (const auto& ch : cfg.channels) slaves.push_back(start_slave(ch));
        master.emplace(std::vector<std::string>{test::bin_path("cupola-master"), "--config", config, "--frames",
                                                std::to_string(frames), "--events", events(), "--stats",
                                                dir + "/master.stats.json"},
                       dir + "/master.log", headless);
    }
    ChildProcess start_slave(const ChannelConfig& ch) {
        return ChildProcess({test::bin_path("cupola-slave"), "--config", config, "--channel", ch.name, "--out",
                             dir + "/" + ch.name, "--idle-timeout", "60", "--present-log", present_log(ch)},
                            dir + "/" + ch.name + ".log", headless);
    }
    std::string present_log(const ChannelConfig& ch) const { return dir + "/" + ch.name + ".present.jsonl"; }
    std::string events() const { return dir + "/events.jsonl"; }
    // Waits for the master and every slave not killed; all exit 0.
    void finish(const std::vector<size_t>& killed = {}) {
        auto mrc = master->wait_for(400s);
        ASSERT_TRUE(mrc.has_value()) << "master did not finish";
        EXPECT_EQ(*mrc, 0) << test::read_text(dir + "/master.log");
        for (size_t i = 0; i < slaves.size(); ++i) {
            if (std::find(killed.begin(), killed.end(), i) != killed.end()) continue;
            auto rc = slaves[i].wait_for(30s);
            ASSERT_TRUE(rc.has_value()) << cfg.channels[i].name << " did not quit";
            EXPECT_EQ(*rc, 0) << test::read_text(dir + "/" + cfg.channels[i].name + ".log");
        }
    }

    const std::vector<std::string> headless = {"DISPLAY", "WAYLAND_DISPLAY"};
    std::string dir, config;
    ClusterConfig cfg;
    std::vector<ChildProcess> slaves;
    std::optional<ChildProcess> master;
};

// The master's frame events by frame: which channels reported ready in time, and when.
std::map<uint64_t, std::map<int, uint64_t>> ready_by_frame(const std::string& events_file) {
    std::map<uint64_t, std::map<int, uint64_t>> out;
    for (const auto& e : test::read_events(events_file)) {
        if (e.value("event", "") != "frame") continue;
        auto& frame = out[e.at("frame").get<uint64_t>()];
        for (const auto& [id, rep] : e.at("channels").items()) frame[std::stoi(id)] = rep.at("ready_ns");
    }
    return out;
}

// No channel shows frame N before every channel the master counted for N was ready.
void expect_no_present_before_every_ready(const std::map<uint64_t, std::map<int, uint64_t>>& ready,
                                          const std::map<int, PresentLog>& logs) {
    int frames_checked = 0;
    for (const auto& [f, channels] : ready) {
        ASSERT_FALSE(channels.empty()) << "frame " << f;
        uint64_t last_ready = 0;
        for (const auto& [id, r] : channels) {
            EXPECT_GT(r, 0u) << "channel " << id << " reported no ready time for frame " << f;
            last_ready = std::max(last_ready, r);
        }
        for (const auto& [id, log] : logs) {
            auto s = log.find(f);
            if (s == log.end()) continue;
            EXPECT_GE(s->second.present_ns, last_ready)
                << "channel " << id << " showed frame " << f << " " << (last_ready - s->second.present_ns)
                << " ns before the last channel was ready";
        }
        ++frames_checked;
    }
    EXPECT_GT(frames_checked, 0);
}

}  // namespace

TEST(SwapLock, NoSlavePresentsAFrameBeforeEveryLiveSlaveIsReady) {
    const std::string dir = test::scratch_dir("swap_lock");
    const int frames = 300;
    SwapLockCluster c(dir, 48130, frames, {{"swap_lock", true}});
    c.finish();
    if (HasFatalFailure()) return;

    std::map<int, PresentLog> logs;
    for (const auto& ch : c.cfg.channels) logs[ch.id] = read_present_log(c.present_log(ch));
    const auto ready = ready_by_frame(c.events());
    ASSERT_EQ(ready.size(), static_cast<size_t>(frames));
    for (const auto& [f, channels] : ready) EXPECT_EQ(channels.size(), c.cfg.channels.size()) << "frame " << f;
    for (const auto& [id, log] : logs) {
        EXPECT_EQ(log.size(), static_cast<size_t>(frames)) << "channel " << id << " did not show every frame";
        for (const auto& [f, s] : log) {
            EXPECT_NE(s.cause, "unlocked") << f;
            // The slave's own ready time is the one it reported.
            if (ready.count(f) && ready.at(f).count(id)) {
                EXPECT_EQ(s.ready_ns, ready.at(f).at(id)) << f;
            }
        }
    }
    expect_no_present_before_every_ready(ready, logs);

    // The master's skew is what the slaves' logs give: every frame but the last (its present
    // time would come with a report of the next frame) is measured, and the largest skew agrees.
    const nlohmann::json stats = nlohmann::json::parse(test::read_text(dir + "/master.stats.json"));
    const nlohmann::json& p = stats.at("presentation");
    EXPECT_EQ(p.at("swap_lock"), true);
    EXPECT_EQ(p.at("frames"), frames - 1);
    EXPECT_EQ(stats.at("master").at("presents_sent"), frames);
    uint64_t max_skew_ns = 0;
    for (uint64_t f = 0; f + 1 < static_cast<uint64_t>(frames); ++f) {
        uint64_t lo = std::numeric_limits<uint64_t>::max(), hi = 0;
        for (const auto& [id, log] : logs) {
            lo = std::min(lo, log.at(f).present_ns);
            hi = std::max(hi, log.at(f).present_ns);
        }
        max_skew_ns = std::max(max_skew_ns, hi - lo);
    }
    EXPECT_NEAR(p.at("skew_ms").at("max").get<double>(), max_skew_ns / 1e6, 1e-6);
    EXPECT_LE(p.at("skew_ms").at("median").get<double>(), p.at("skew_ms").at("p99").get<double>());
    for (const auto& ch : c.cfg.channels) EXPECT_TRUE(p.at("wait_ms").contains(std::to_string(ch.id))) << ch.name;
}

TEST(SwapLock, KilledSlaveDelaysThePresentByAtMostTheChannelTimeout) {
    const std::string dir = test::scratch_dir("swap_lock_kill");
    const int frames = 40;
    const int timeout_ms = 300;
    SwapLockCluster c(dir, 48140, frames, {{"swap_lock", true}, {"channel_timeout_ms", timeout_ms}});
    const size_t victim = 2;
    const ChannelConfig& vch = c.cfg.channels[victim];
    ASSERT_TRUE(test::wait_until([&] { return test::read_events(c.present_log(vch)).size() >= 10; }, 120s))
        << "the victim never showed 10 frames";
    c.slaves[victim].kill(SIGKILL);
    ASSERT_TRUE(c.slaves[victim].wait_for(5s).has_value());
    c.finish({victim});
    if (HasFatalFailure()) return;

    bool dropped = false;
    for (const auto& e : test::read_events(c.events()))
        if (e.value("event", "") == "channel_dropped" && e.value("channel", -1) == vch.id) dropped = true;
    EXPECT_TRUE(dropped) << test::read_text(dir + "/master.log");

    std::map<int, PresentLog> logs;
    for (const auto& ch : c.cfg.channels) logs[ch.id] = read_present_log(c.present_log(ch));
    const auto ready = ready_by_frame(c.events());
    ASSERT_EQ(ready.size(), static_cast<size_t>(frames));
    expect_no_present_before_every_ready(ready, logs);
    // The others went on: every frame shown by each survivor, none waiting past the channel
    // timeout (plus slack for a loaded machine) after the last survivor was ready.
    const uint64_t bound_ns = (timeout_ms + 3000) * 1000000ull;
    for (const auto& ch : c.cfg.channels) {
        if (ch.id == vch.id) continue;
        const PresentLog& log = logs.at(ch.id);
        // (a slow first render may have had it dropped too, for a frame or two at the start)
        for (const auto& [f, channels] : ready)
            if (channels.count(ch.id)) {
                EXPECT_TRUE(log.count(f)) << ch.name << " reported frame " << f << ", never showed it";
            }
        EXPECT_TRUE(log.count(frames - 1)) << ch.name;
        for (const auto& [f, s] : log) {
            uint64_t last_ready = 0;
            for (const auto& [id, other] : logs)
                if (id != vch.id && other.count(f)) last_ready = std::max(last_ready, other.at(f).ready_ns);
            EXPECT_LE(s.present_ns - std::min(s.present_ns, last_ready), bound_ns) << ch.name << " frame " << f;
        }
    }
    EXPECT_LT(logs.at(vch.id).size(), static_cast<size_t>(frames));
}

// The master's measurement from the reports alone (master/present_skew.hpp).
TEST(SwapLock, SkewReleaseAndWaitComeFromTheReportsOfTheNextFrame) {
    auto report = [](int ch, uint64_t frame, uint64_t ready_ns, std::optional<std::pair<uint64_t, uint64_t>> shown) {
        FrameReport r;
        r.channel = static_cast<uint16_t>(ch);
        r.frame = frame;
        PresentTiming t;
        t.ready_ns = ready_ns;
        if (shown) t = PresentTiming{ready_ns, true, shown->first, shown->second};
        r.presentation = t;
        return r;
    };
    // Frame 7: ready at 1.0, 1.5 and 3.0 ms; shown at 4.0, 4.5 and 6.0 ms (reported with frame 8).
    const std::map<int, FrameReport> frame7 = {
        {0, report(0, 7, 1000000, {})}, {1, report(1, 7, 1500000, {})}, {2, report(2, 7, 3000000, {})}};
    const std::map<int, FrameReport> frame8 = {{0, report(0, 8, 9000000, {{7, 4000000}})},
                                               {1, report(1, 8, 9000000, {{7, 4500000}})},
                                               {2, report(2, 8, 9000000, {{7, 6000000}})}};
    PresentSkew skew;
    EXPECT_FALSE(skew.add(frame7, {})) << "nothing shown yet";
    const auto fp = skew.add(frame8, frame7);
    ASSERT_TRUE(fp);
    EXPECT_EQ(fp->frame, 7u);
    EXPECT_EQ(fp->channels, 3);
    EXPECT_DOUBLE_EQ(fp->skew_ms, 2.0);
    EXPECT_DOUBLE_EQ(fp->release_ms, 1.0);
    EXPECT_DOUBLE_EQ(fp->wait_ms.at(0), 3.0);
    EXPECT_DOUBLE_EQ(fp->wait_ms.at(2), 3.0);
    // A channel that showed an older frame (it missed one) is left out of frame 7's figures, and
    // a report without the block (an older slave) too.
    std::map<int, FrameReport> mixed = frame8;
    mixed[1] = report(1, 8, 9000000, {{5, 100}});
    mixed[2].presentation.reset();
    EXPECT_FALSE(skew.add(mixed, frame7)) << "one channel alone has no skew";
    const nlohmann::json j = skew.to_json();
    EXPECT_EQ(j.at("frames"), 1);
    EXPECT_DOUBLE_EQ(j.at("skew_ms").at("median").get<double>(), 2.0);
    EXPECT_DOUBLE_EQ(j.at("wait_ms").at("1").at("max").get<double>(), 3.0);
    std::deque<double> samples;
    for (int i = 1; i <= 200; ++i) samples.push_back(i);
    const nlohmann::json s = percentile_summary(samples);
    EXPECT_EQ(s.at("median"), 100.0);
    EXPECT_EQ(s.at("p99"), 198.0);
    EXPECT_EQ(s.at("max"), 200.0);
}

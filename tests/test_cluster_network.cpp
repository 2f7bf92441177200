// The cluster over a real network under real faults: master, relay, three slave hosts and an
// attacker in network namespaces joined by a bridge (support/netns_cluster.hpp). Loss is injected
// with nftables, reordering, duplication and delay by a relay process, link flaps with
// `ip link set down/up`; crashes with SIGKILL/SIGSTOP. Every run checks that each channel wrote
// every frame and that, for each frame, every channel rendered the master's snapshot (no mixed
// frames), and that the counters name the faults that were injected. Skips without root.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <optional>
#include <random>
#include <thread>

#include "config/cluster_config.hpp"
#include "net/key_file.hpp"
#include "net/udp_socket.hpp"
#include "support/netns_cluster.hpp"
#include "wire/packet.hpp"

using namespace cupola;
using namespace std::chrono_literals;
using test::NetnsCluster;
using test::NetnsClusterOptions;

namespace {

constexpr int kFrames = 300;

#define SKIP_WITHOUT_NETNS()                                                   \
    do {                                                                       \
        const std::string why = test::NetnsTestbed::unavailable_reason();      \
        if (!why.empty()) GTEST_SKIP() << "needs network namespaces: " << why; \
    } while (0)

// Every channel wrote every frame in [first, end), each from the master's snapshot for it.
void expect_no_gap_no_mixed_frame(const NetnsCluster& c, uint64_t first, uint64_t end,
                                  const std::map<uint64_t, std::string>& master,
                                  const std::vector<int>& channels = {0, 1, 2, 3}) {
    const auto written = c.written_frames();
    int missing = 0, mixed = 0;
    for (int id : channels) {
        const auto it = written.find(id);
        for (uint64_t f = first; f < end; ++f) {
            const auto m = master.find(f);
            ASSERT_NE(m, master.end()) << "the master has no frame " << f;
            if (it == written.end() || !it->second.count(f)) {
                if (++missing <= 5) ADD_FAILURE() << "channel " << id << " did not write frame " << f;
                continue;
            }
            if (it->second.at(f) != m->second && ++mixed <= 5)
                ADD_FAILURE() << "channel " << id << " frame " << f << " is from snapshot " << it->second.at(f)
                              << ", the master sent " << m->second;
        }
    }
    EXPECT_EQ(missing, 0);
    EXPECT_EQ(mixed, 0);
}

nlohmann::json slave_stats(const NetnsCluster& c, int id) { return c.stats(c.stats_file(id)); }

uint64_t sum_over_slaves(const NetnsCluster& c, const std::string& section, const std::string& key) {
    uint64_t s = 0;
    for (int id = 0; id < NetnsCluster::kChannels; ++id) s += slave_stats(c, id)[section][key].get<uint64_t>();
    return s;
}

void expect_no_security_rejections(const nlohmann::json& wire, const std::string& who) {
    EXPECT_EQ(wire["forged"], 0) << who;
    EXPECT_EQ(wire["foreign"], 0) << who;
    EXPECT_EQ(wire["replayed"], 0) << who;
    EXPECT_EQ(wire["malformed"], 0) << who;
}

// Waits for master and slaves to finish; "" when every process exited 0, else what went wrong.
std::string finish_run(NetnsCluster& c) {
    std::string failures;
    c.finish(failures);
    return failures;
}

// No node saw a forged, replayed, foreign or malformed datagram.
void expect_no_security_rejections_anywhere(const NetnsCluster& c) {
    expect_no_security_rejections(c.stats(c.master_stats())["wire"], "master");
    for (int id = 0; id < NetnsCluster::kChannels; ++id)
        expect_no_security_rejections(slave_stats(c, id)["wire"], "slave " + std::to_string(id));
}

}  // namespace

class ClusterLoss : public ::testing::TestWithParam<int> {};

TEST_P(ClusterLoss, EveryChannelRendersEveryFrameFromTheSameSnapshot) {
    SKIP_WITHOUT_NETNS();
    const int percent = GetParam();
    NetnsCluster c("loss" + std::to_string(percent), NetnsClusterOptions{});
    for (const char* h : {"s1", "s2", "s3"})
        c.bed.set_loss(h, percent, NetnsCluster::kSnapshotPort, NetnsCluster::kSnapshotPort);
    c.bed.set_loss("master", percent, NetnsCluster::kReportPort, NetnsCluster::kReportPort);
    c.start_all(kFrames);
    ASSERT_EQ(finish_run(c), "");

    uint64_t injected = c.bed.dropped_packets("master");
    for (const char* h : {"s1", "s2", "s3"}) injected += c.bed.dropped_packets(h);
    EXPECT_GT(injected, 0u);
    expect_no_gap_no_mixed_frame(c, 0, kFrames, c.master_hashes());

    // The counters name the fault: losses cost resends, nothing looks forged or replayed.
    const auto m = c.stats(c.master_stats());
    EXPECT_GT(m["master"]["snapshot_resends"].get<uint64_t>(), 0u) << m.dump(2);
    EXPECT_EQ(m["master"]["channel_drops"], 0) << m.dump(2);
    EXPECT_EQ(m["master"]["frames"], kFrames);
    expect_no_security_rejections(m["wire"], "master");
    for (int id = 0; id < NetnsCluster::kChannels; ++id) {
        const auto s = slave_stats(c, id);
        expect_no_security_rejections(s["wire"], "slave " + std::to_string(id));
        EXPECT_EQ(s["slave"]["frames_rendered"], kFrames) << s.dump(2);
        EXPECT_EQ(s["slave"]["missed_frames"], 0) << s.dump(2);
    }
    // A lost report makes the master resend a snapshot the slave already rendered: it repeats the report.
    EXPECT_GT(sum_over_slaves(c, "slave", "resent_snapshots"), 0u);
    std::printf("loss %d %%: %llu datagrams dropped by nftables, %llu snapshot resends\n", percent,
                static_cast<unsigned long long>(injected),
                static_cast<unsigned long long>(m["master"]["snapshot_resends"].get<uint64_t>()));
}

INSTANTIATE_TEST_SUITE_P(Percent, ClusterLoss, ::testing::Values(1, 5, 20),
                         [](const auto& info) { return std::to_string(info.param) + "percent"; });

TEST(ClusterRelay, ReorderedDatagramsAreReassembledAndCounted) {
    SKIP_WITHOUT_NETNS();
    NetnsClusterOptions o;
    o.max_datagram_bytes = 300;  // snapshots travel in several fragments, so reordering hits them
    o.relay_faults = {"--reorder", "0.3"};
    NetnsCluster c("reorder", o);
    c.start_all(kFrames);
    ASSERT_EQ(finish_run(c), "");
    expect_no_gap_no_mixed_frame(c, 0, kFrames, c.master_hashes());
    const auto relay = c.stats(c.dir + "/relay-snapshots.json");
    EXPECT_GT(relay["reordered"].get<uint64_t>(), 0u);
    EXPECT_GT(sum_over_slaves(c, "wire", "reordered"), 0u);
    EXPECT_EQ(sum_over_slaves(c, "wire", "duplicates"), 0u);
    expect_no_security_rejections_anywhere(c);
}

TEST(ClusterRelay, DuplicatedDatagramsAreDroppedAndCounted) {
    SKIP_WITHOUT_NETNS();
    NetnsClusterOptions o;
    o.max_datagram_bytes = 300;
    o.relay_faults = {"--duplicate", "0.3"};
    NetnsCluster c("dup", o);
    c.start_all(kFrames);
    ASSERT_EQ(finish_run(c), "");
    expect_no_gap_no_mixed_frame(c, 0, kFrames, c.master_hashes());
    const auto relay_s = c.stats(c.dir + "/relay-snapshots.json");
    const auto relay_r = c.stats(c.dir + "/relay-reports.json");
    EXPECT_GT(relay_s["duplicated"].get<uint64_t>(), 0u);
    // Every copy the relay made is dropped as a duplicate by the receivers (each slave process
    // on the multicast group sees every snapshot copy), none is taken for a replay.
    EXPECT_GT(sum_over_slaves(c, "wire", "duplicates"), 0u);
    const auto m = c.stats(c.master_stats());
    // The master counts every copy of the reports, except a few of the quit confirmations that
    // arrive after it wrote its final stats.
    const auto dup_m = m["wire"]["duplicates"].get<uint64_t>(), dup_r = relay_r["duplicated"].get<uint64_t>();
    EXPECT_LE(dup_m, dup_r);
    EXPECT_GE(dup_m + 12, dup_r) << m.dump(2);
    expect_no_security_rejections(m["wire"], "master");
    for (int id = 0; id < NetnsCluster::kChannels; ++id) {
        const auto s = slave_stats(c, id);
        expect_no_security_rejections(s["wire"], "slave " + std::to_string(id));
        EXPECT_EQ(s["slave"]["frames_rendered"], kFrames);
    }
}

TEST(ClusterRelay, DelayWithJitterOnBothDirections) {
    SKIP_WITHOUT_NETNS();
    NetnsClusterOptions o;
    o.relay_faults = {"--delay-ms", "1", "--jitter-ms", "19"};
    o.resend_interval_ms = 60;  // longer than a round trip, so resends mean loss, not delay
    NetnsCluster c("delay", o);
    c.start_all(kFrames);
    ASSERT_EQ(finish_run(c), "");
    expect_no_gap_no_mixed_frame(c, 0, kFrames, c.master_hashes());
    const auto relay = c.stats(c.dir + "/relay-snapshots.json");
    EXPECT_GE(relay["max_hold_ms"].get<double>(), 10.0);
    // The master's frame time includes both delays: at least 2 ms per frame.
    double sum_ms = 0;
    int n = 0;
    for (const auto& e : test::read_events(c.dir + "/master.events.jsonl"))
        if (e.value("event", "") == "frame") sum_ms += e["frame_ms"].get<double>(), ++n;
    ASSERT_EQ(n, kFrames);
    EXPECT_GT(sum_ms / n, 2.0);
    for (int id = 0; id < NetnsCluster::kChannels; ++id)
        expect_no_security_rejections(slave_stats(c, id)["wire"], "slave " + std::to_string(id));
}

TEST(ClusterFaults, LinkFlapCostsResendsNotFrames) {
    SKIP_WITHOUT_NETNS();
    NetnsCluster c("flap", NetnsClusterOptions{});
    c.start_all(kFrames);
    ASSERT_TRUE(c.wait_for_frame(2, 100));
    c.bed.link_down("s2");
    std::this_thread::sleep_for(700ms);
    c.bed.link_up("s2");
    ASSERT_EQ(finish_run(c), "");
    expect_no_gap_no_mixed_frame(c, 0, kFrames, c.master_hashes());
    const auto m = c.stats(c.master_stats());
    EXPECT_GE(m["master"]["snapshot_resends"].get<uint64_t>(), 5u) << m.dump(2);  // 700 ms at 20 ms intervals
    EXPECT_EQ(m["master"]["channel_drops"], 0);                                   // shorter than the channel timeout
    expect_no_security_rejections(m["wire"], "master");
}

// How fast a restarted slave renders again is measured by benchmarks/slave_restart (1 s is the
// bound; BENCHMARKS.md has the figures): start-up is the dynamic loader, EGL and the scene's maps
// on a shared 2-core VM, which a test cannot time reliably. Here: it renders again, neither
// restart waited for a timeout (the better of two within twice the bound, each within 5 s), and
// nobody has a gap.
TEST(ClusterFaults, KilledSlaveRestartedRendersAgainOthersHaveNoGap) {
    SKIP_WITHOUT_NETNS();
    NetnsCluster c("crash", NetnsClusterOptions{});
    c.start_all(kFrames);
    const auto first_s = c.kill_and_restart(3, 100, "-restarted");
    ASSERT_TRUE(first_s.has_value());
    const auto second_s = c.kill_and_restart(3, 180, "-restarted-again");
    ASSERT_TRUE(second_s.has_value());
    std::printf("restarted slave wrote its first frame %.3f s and %.3f s after it was started\n", *first_s, *second_s);
    EXPECT_LT(std::min(*first_s, *second_s), 2.0);
    EXPECT_LT(std::max(*first_s, *second_s), 5.0);

    ASSERT_EQ(finish_run(c), "");
    // The barrier waited for the channel instead of dropping it: nobody, the victim included, has a gap.
    expect_no_gap_no_mixed_frame(c, 0, kFrames, c.master_hashes());
    const auto m = c.stats(c.master_stats());
    EXPECT_EQ(m["master"]["channel_restarts"], 2) << m.dump(2);
    EXPECT_EQ(m["master"]["channel_drops"], 0) << m.dump(2);
}

TEST(ClusterFaults, RestartedMasterResumesAndSlavesReRegisterWithoutRestarting) {
    SKIP_WITHOUT_NETNS();
    NetnsCluster c("mrestart", NetnsClusterOptions{});
    c.start_all(kFrames);
    std::vector<pid_t> pids;
    for (auto& s : c.slaves) pids.push_back(s.pid());
    ASSERT_TRUE(c.wait_for_frame(0, 100));
    c.master->kill(SIGKILL);
    ASSERT_TRUE(c.master->wait_for(5s).has_value());
    std::this_thread::sleep_for(1500ms);  // the slaves notice the silence
    c.master.emplace(c.start_master(kFrames, "master2"));
    ASSERT_EQ(finish_run(c), "");

    uint64_t resumed_at = 0;
    for (const auto& e : test::read_events(c.dir + "/master2.events.jsonl"))
        if (e.value("event", "") == "resumed") resumed_at = e["frame"].get<uint64_t>();
    EXPECT_GT(resumed_at, 100u) << "the second master did not resume the show";
    // Every frame once: from the first master before the resume point, from the second after.
    auto expected = c.master_hashes("master2");
    for (const auto& [f, h] : c.master_hashes())
        if (f < resumed_at) expected[f] = h;
    // A frame the first master completed but was killed before logging: the channels must still agree.
    const auto written = c.written_frames();
    for (uint64_t f = 0; f < kFrames; ++f)
        if (!expected.count(f) && written.count(0) && written.at(0).count(f)) expected[f] = written.at(0).at(f);
    expect_no_gap_no_mixed_frame(c, 0, kFrames, expected);
    for (int id = 0; id < NetnsCluster::kChannels; ++id) {
        EXPECT_EQ(c.slaves[id].pid(), pids[id]);
        const auto s = slave_stats(c, id);
        EXPECT_EQ(s["slave"]["master_sessions"], 2) << s.dump(2);  // welcomed by both masters
    }
    const auto m2 = c.stats(c.master_stats());
    EXPECT_EQ(m2["master"]["channel_joins"], 4) << m2.dump(2);
    EXPECT_GT(m2["master"]["welcomes_sent"].get<uint64_t>(), 0u);
}

TEST(ClusterFaults, WedgedSlaveIsTimedOutOthersGoOnItRejoinsWhenItRecovers) {
    SKIP_WITHOUT_NETNS();
    NetnsClusterOptions o;
    o.channel_timeout_ms = 800;
    NetnsCluster c("wedge", o);
    c.start_all(kFrames);
    ASSERT_TRUE(c.wait_for_frame(2, 60));
    c.slaves[2].kill(SIGSTOP);
    std::this_thread::sleep_for(2500ms);
    c.slaves[2].kill(SIGCONT);
    ASSERT_EQ(finish_run(c), "");
    const auto hashes = c.master_hashes();
    expect_no_gap_no_mixed_frame(c, 0, kFrames, hashes, {0, 1, 3});
    uint64_t dropped_at = 0, rejoined_at = 0;
    for (const auto& e : test::read_events(c.dir + "/master.events.jsonl")) {
        if (e.value("channel", -1) != 2) continue;
        if (e.value("event", "") == "channel_dropped" && !dropped_at) dropped_at = e["frame"].get<uint64_t>();
        if (e.value("event", "") == "channel_joined" && dropped_at && !rejoined_at)
            rejoined_at = e["frame"].get<uint64_t>();
    }
    ASSERT_GT(dropped_at, 0u) << "the wedged channel was never dropped";
    ASSERT_GT(rejoined_at, dropped_at) << "it never rejoined";
    // After it rejoined it rendered every frame again, from the right snapshots.
    expect_no_gap_no_mixed_frame(c, rejoined_at + 1, kFrames, hashes, {2});
    const auto s = slave_stats(c, 2);
    EXPECT_GT(s["slave"]["missed_frames"].get<uint64_t>(), 0u) << s.dump(2);
    const auto m = c.stats(c.master_stats());
    EXPECT_GE(m["master"]["channel_drops"].get<uint64_t>(), 1u);
}

TEST(ClusterSecurity, ForgedReplayedTruncatedAndFlippedPacketsAreRejectedCountedAndChangeNothing) {
    SKIP_WITHOUT_NETNS();
    NetnsCluster c("attack", NetnsClusterOptions{});
    const ClusterConfig cfg = load_cluster_config(c.master_config);
    const AuthKey key = load_key_file(cfg.key_file, true);
    const sockaddr_in group = make_address("239.255.61.1", NetnsCluster::kSnapshotPort);
    const sockaddr_in master_port = make_address(c.bed.host("master").address, NetnsCluster::kReportPort);

    // The attacker's host listens to the cluster's multicast like any machine on the LAN could.
    const int rx = c.bed.open_socket("attacker", SOCK_DGRAM);
    const int one = 1;
    setsockopt(rx, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    ASSERT_EQ(::bind(rx, reinterpret_cast<const sockaddr*>(&group), sizeof group), 0);
    ip_mreq mreq{};
    mreq.imr_multiaddr = group.sin_addr;
    mreq.imr_interface.s_addr = htonl(INADDR_ANY);
    ASSERT_EQ(setsockopt(rx, IPPROTO_IP, IP_ADD_MEMBERSHIP, &mreq, sizeof mreq), 0);
    const int tx = c.bed.open_socket("attacker", SOCK_DGRAM);
    auto send = [&](const sockaddr_in& to, const std::vector<uint8_t>& d) {
        ::sendto(tx, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
        std::this_thread::sleep_for(1ms);
    };

    c.start_all(kFrames);
    // Record 20 authentic snapshot datagrams (the test knows the key only to pick them out).
    const PacketCodec reader(cfg.cluster_id, key);
    std::vector<std::vector<uint8_t>> recorded;
    uint64_t master_session = 0;
    timeval tv{30, 0};
    setsockopt(rx, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    while (recorded.size() < 20) {
        std::vector<uint8_t> buf(65536);
        const ssize_t n = ::recv(rx, buf.data(), buf.size(), 0);
        ASSERT_GT(n, 0) << "nothing to record";
        buf.resize(static_cast<size_t>(n));
        auto p = reader.decode(buf.data(), buf.size());
        if (!p.packet || p.packet->header.type != PacketType::Snapshot) continue;
        master_session = p.packet->header.session;
        recorded.push_back(buf);
    }
    ::close(rx);
    std::this_thread::sleep_for(700ms);  // longer than the duplicate horizon: a repeat now is a replay

    const int kEach = 10;
    std::mt19937 rng(11);
    int to_slaves = 0, to_master = 0;
    // Replays of authentic datagrams.
    for (int i = 0; i < kEach; ++i, ++to_slaves) send(group, recorded[i]);
    // Forged: the right cluster and session, the wrong key; to the slaves and to the master.
    const PacketCodec forger(
        cfg.cluster_id,
        [&] {
            AuthKey k = key;
            k[5] ^= 0x20;
            return k;
        }(),
        master_session);
    uint32_t seq = 1u << 30;
    for (int i = 0; i < kEach; ++i) {
        send(group, forger.encode(PacketType::Quit, kMasterSender, 5, {}, 1400, &seq)[0]), ++to_slaves;
        send(master_port, forger.encode(PacketType::FrameDone, 1, 5, {1, 2, 3}, 1400, &seq)[0]), ++to_master;
    }
    // Bit-flipped authentic datagrams (never in the length fields, so each must fail authentication).
    for (int i = 0; i < kEach; ++i) {
        auto d = recorded[10 + i];
        size_t pos;
        do pos = 12 + rng() % (d.size() - 12);
        while (pos >= 56 && pos < 60);
        d[pos] ^= static_cast<uint8_t>(1u << (rng() % 8));
        send(group, d), ++to_slaves;
        send(master_port, d), ++to_master;
    }
    // Truncated.
    for (int i = 0; i < kEach; ++i) {
        auto d = recorded[i];
        d.resize(d.size() - 1 - i);
        send(group, d), ++to_slaves;
        send(master_port, d), ++to_master;
    }
    // Another cluster with the same key, and another protocol version, on the same network.
    const PacketCodec other_cluster(cfg.cluster_id + 1, key, master_session);
    for (int i = 0; i < kEach; ++i) {
        send(group, other_cluster.encode(PacketType::Quit, kMasterSender, 5, {}, 1400, &seq)[0]), ++to_slaves;
        auto v = recorded[i];
        v[4] = 1;
        send(group, v), ++to_slaves;
        send(master_port, v), ++to_master;
    }

    ASSERT_EQ(finish_run(c), "");
    ::close(tx);
    // Nothing changed: every channel rendered exactly the master's frames, once each.
    expect_no_gap_no_mixed_frame(c, 0, kFrames, c.master_hashes());
    for (int id = 0; id < NetnsCluster::kChannels; ++id) {
        const auto s = slave_stats(c, id);
        const auto& w = s["wire"];
        EXPECT_EQ(s["slave"]["frames_rendered"], kFrames) << s.dump(2);
        EXPECT_EQ(s["slave"]["malformed_snapshots"], 0) << s.dump(2);
        EXPECT_EQ(w["replayed"], kEach) << s.dump(2);
        EXPECT_EQ(w["forged"], 2 * kEach) << s.dump(2);   // wrong key + bit flips
        EXPECT_EQ(w["malformed"], kEach) << s.dump(2);    // truncated
        EXPECT_EQ(w["foreign"], 2 * kEach) << s.dump(2);  // other cluster, other version
        EXPECT_EQ(w["rejected"], to_slaves) << s.dump(2);
    }
    const auto m = c.stats(c.master_stats());
    EXPECT_EQ(m["wire"]["forged"], 2 * kEach) << m.dump(2);
    EXPECT_EQ(m["wire"]["malformed"], kEach) << m.dump(2);
    EXPECT_EQ(m["wire"]["foreign"], kEach) << m.dump(2);
    EXPECT_EQ(m["wire"]["rejected"], to_master) << m.dump(2);
    EXPECT_EQ(m["master"]["frames"], kFrames);
}

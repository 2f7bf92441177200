// A real slave process fed by a hand-driven master: garbage datagrams, a wrong-key packet and an
// authentic snapshot that names a body the scene lacks are all refused and counted; the slave
// keeps going, renders the next good snapshot, reports the counts, and quits when told.
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "image/frame_image.hpp"
#include "master_node.hpp"
#include "net/key_file.hpp"
#include "net/wire_endpoint.hpp"
#include "support/cluster_fixture.hpp"
#include "support/wire_handshake.hpp"
#include "util/child_process.hpp"
#include "wire/reports.hpp"

using namespace cupola;
using namespace std::chrono_literals;

TEST(SlaveInput, BadPacketsAreCountedAndTheSlaveGoesOn) {
    const std::string dir = test::scratch_dir("slave_input");
    const std::string config = test::write_test_cluster(
        dir, 47860, 32, 32,
        {{"network", {{"transport", "unicast"}}},
         {"dome", {{"require_full_coverage", false}}},
         {"channels",
          {{{"id", 0},
            {"name", "solo"},
            {"unicast_address", "127.0.0.1:47865"},
            {"orientation", {{"pitch_deg", 90}}},
            {"fov", {{"left_deg", 40}, {"right_deg", 40}, {"up_deg", 40}, {"down_deg", 40}}}}}}});
    const ClusterConfig cfg = load_cluster_config(config);
    const SceneConfig scene = load_scene_config(cfg.scene_file);
    const ShowScript show = ShowScript::load(cfg.show_file, scene);
    const AuthKey key = load_key_file(cfg.key_file);
    WireEndpoint master = open_master_endpoint(cfg, key, new_session_nonce());
    ChildProcess slave({test::bin_path("cupola-slave"), "--config", config, "--channel", "solo", "--out", dir + "/solo",
                        "--idle-timeout", "60"},
                       dir + "/slave.log", {"DISPLAY", "WAYLAND_DISPLAY"});

    ASSERT_EQ(test::welcome_one_slave(master, cfg, 60000), 0) << "the slave never completed the handshake";
    const auto to = snapshot_destinations(cfg);

    // Garbage and a packet signed with another key.
    UdpSocket raw;
    const std::vector<uint8_t> junk = {1, 2, 3, 4, 5, 6, 7, 8};
    raw.send_to(to[0], junk.data(), junk.size());
    AuthKey other = key;
    other[0] ^= 1;
    PacketCodec forger(cfg.cluster_id, other);
    uint32_t seq = 0;
    const Snapshot good0 = make_frame_snapshot(cfg, scene, show, 0);
    for (const auto& d : forger.encode(PacketType::Snapshot, kMasterSender, 0, encode_snapshot(good0), 1400, &seq))
        raw.send_to(to[0], d.data(), d.size());
    // Authentic, but names body 99 of a 3-body scene.
    Snapshot bad = good0;
    bad.bodies[0].id = 99;
    master.send(PacketType::Snapshot, 0, encode_snapshot(bad), to);
    // (A slave that finds a newer snapshot queued renders only that one: give it time to read this.)
    std::this_thread::sleep_for(300ms);
    // Then a good frame 1.
    const Snapshot good1 = make_frame_snapshot(cfg, scene, show, 1);
    const auto payload1 = encode_snapshot(good1);
    std::optional<FrameReport> report;
    for (int attempt = 0; attempt < 100 && !report; ++attempt) {
        master.send(PacketType::Snapshot, 1, payload1, to);
        while (auto m = master.receive(500)) {
            if (m->message.type != PacketType::FrameDone) continue;
            report = decode_frame_report(m->message.payload);
            break;
        }
    }
    ASSERT_TRUE(report) << test::read_text(dir + "/slave.log");
    EXPECT_EQ(report->frame, 1u);
    EXPECT_EQ(report->snapshot_hash, snapshot_hash(payload1));
    EXPECT_GE(report->packets_rejected, 3u);  // junk + forged + the snapshot with a bad body id
    master.send(PacketType::Quit, 1, {}, to);
    master.send(PacketType::Quit, 1, {}, to);
    auto rc = slave.wait_for(30s);
    ASSERT_TRUE(rc.has_value());
    EXPECT_EQ(*rc, 0) << test::read_text(dir + "/slave.log");
    EXPECT_TRUE(std::filesystem::exists(dir + "/solo/" + frame_file_name(1, "png")));
    EXPECT_FALSE(std::filesystem::exists(dir + "/solo/" + frame_file_name(0, "png")));
    const std::string log = test::read_text(dir + "/slave.log");
    EXPECT_NE(log.find("body id 99"), std::string::npos) << log;
}

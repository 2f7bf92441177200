// A real slave process fed by a hand-driven master: its "ready N" report for a frame goes out only
// once the frame's files are on disk, so a slave killed right after a report loses no frame the
// master counted (a restarted slave renders the master's current frame, not the ones before).
#include <gtest/gtest.h>

#include <filesystem>

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

TEST(SlaveReports, ReadyGoesOutOnlyOnceTheFrameFilesAreOnDisk) {
    const std::string dir = test::scratch_dir("slave_reports_written");
    // 256^2 so that encoding takes a few ms: a report sent before the write would be caught.
    const std::string config = test::write_test_cluster(
        dir, 47870, 256, 256,
        {{"network", {{"transport", "unicast"}}},
         {"dome", {{"require_full_coverage", false}}},
         {"output", {{"formats", {"png", "exr"}}}},
         {"channels",
          {{{"id", 0},
            {"name", "solo"},
            {"unicast_address", "127.0.0.1:47875"},
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

    for (uint64_t frame = 1; frame <= 4; ++frame) {
        const auto payload = encode_snapshot(make_frame_snapshot(cfg, scene, show, frame));
        std::optional<FrameReport> report;
        for (int attempt = 0; attempt < 100 && !report; ++attempt) {
            master.send(PacketType::Snapshot, frame, payload, to);
            while (auto m = master.receive(500)) {
                if (m->message.type != PacketType::FrameDone) continue;
                const FrameReport r = decode_frame_report(m->message.payload);
                if (r.frame != frame) continue;
                report = r;
                // Checked the moment the report arrives, before anything else.
                for (const char* ext : {"png", "exr"})
                    EXPECT_TRUE(std::filesystem::exists(dir + "/solo/" + frame_file_name(frame, ext)))
                        << "frame " << frame << " reported ready before its " << ext << " was written";
                break;
            }
        }
        ASSERT_TRUE(report) << test::read_text(dir + "/slave.log");
        EXPECT_EQ(report->snapshot_hash, snapshot_hash(payload));
        EXPECT_GT(report->write_ms, 0.0f);  // the write is in the report's time now
        if (frame == 4) break;
        // The swap lock (on by default) holds frame N until "present N".
        master.send(PacketType::Present, frame, encode_present({frame}), to);
    }
    master.send(PacketType::Quit, 4, {}, to);
    master.send(PacketType::Quit, 4, {}, to);
    const auto rc = slave.wait_for(30s);
    ASSERT_TRUE(rc.has_value());
    EXPECT_EQ(*rc, 0) << test::read_text(dir + "/slave.log");
}

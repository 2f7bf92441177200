// The whole device path on the master: an emulated 3D mouse on an emulated USB bus (umockdev),
// read by the master's UsbInput through real libusb, turned into camera motion by the director
// and navigation model, and received as snapshots by a channel at the wire level. Runs under
// umockdev-wrapper (tests/CMakeLists.txt).
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "config/cluster_config.hpp"
#include "master_node.hpp"
#include "net/key_file.hpp"
#include "support/test_support.hpp"
#include "support/umockdev_devices.hpp"
#include "support/wire_channel.hpp"

using namespace cupola;

namespace {

std::string write_config(const std::string& dir) {
    nlohmann::json c = nlohmann::json::parse(test::read_text(test::source_path("configs/loopback-1ch.json")));
    for (const char* k : {"key_file", "scene", "show"}) c[k] = test::source_path("configs/" + c[k].get<std::string>());
    c["frame_rate_hz"] = 50;
    c["network"]["report_port"] = 47977;
    c["channels"][0]["unicast_address"] = "127.0.0.1:47976";
    c["input"] = {{"usb", true}, {"smoothing_s", 0.0}};
    const std::string path = dir + "/cluster.json";
    test::write_text(path, c.dump(2));
    return path;
}

// The camera's motion between two snapshots, in the camera's own frame (+X right, -Z forward).
glm::dvec3 motion_in_camera_frame(const test::Received& a, const test::Received& b) {
    return glm::transpose(glm::mat3_cast(b.orientation)) * (b.offset - a.offset);
}

bool moving(const test::Received& a, const test::Received& b) { return glm::length(b.offset - a.offset) > 1e-3; }

}  // namespace

TEST(UsbNavigation, ReportsMoveTheCameraAsTheySayAndUnplugStopsIt) {
    ASSERT_TRUE(test::UsbTestbed::preloaded()) << "run under umockdev-wrapper (ctest does)";
    const std::string dir = test::scratch_dir("usb_navigation");
    const ClusterConfig cfg = load_cluster_config(write_config(dir));
    test::UsbTestbed bed;
    auto& mouse = bed.add_device(test::space_navigator());
    MasterOptions opt;
    opt.events_file = dir + "/events.jsonl";
    MasterNode master(cfg, opt);
    test::WireChannel channel(cfg, load_key_file(cfg.key_file, false), 1 /* the Earth */);
    std::thread master_thread([&] { master.run(); });
    struct Stop {
        MasterNode& m;
        std::thread& t;
        ~Stop() {
            m.stop();
            t.join();
        }
    } stop_at_exit{master, master_thread};

    auto now = [] { return monotonic_ns(); };
    // The show plays; the cap at rest (inside the dead zone) does not take it over.
    mouse.send_report(test::spacemouse_report(1, 10, -8, 5));
    ASSERT_TRUE(channel.wait(
        now(), [](auto&, auto&) { return true; }, std::chrono::seconds(30)));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_EQ(test::read_text(opt.events_file).find("\"mode\":\"live\""), std::string::npos);

    // Push the cap right (x = +175 of 350): the camera moves along its own +X.
    uint64_t t0 = now();
    mouse.send_report(test::spacemouse_report(1, 175, 0, 0));
    auto hit = channel.wait(t0, moving, std::chrono::seconds(5));
    ASSERT_TRUE(hit) << "the camera did not move after a report";
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    {
        const auto got = channel.received();
        const auto& a = got[got.size() - 3];
        const auto& b = got[got.size() - 2];
        const glm::dvec3 m = motion_in_camera_frame(a, b);
        EXPECT_GT(m.x / glm::length(m), 0.999) << "moved " << m.x << " " << m.y << " " << m.z;
    }
    // Push it away from you (-y in the 3Dconnexion frame, whose y points at the user): along -Z.
    t0 = now();
    mouse.send_report(test::spacemouse_report(1, 0, -175, 0));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    {
        const auto got = channel.received();
        const auto& a = got[got.size() - 3];
        const auto& b = got[got.size() - 2];
        const glm::dvec3 m = motion_in_camera_frame(a, b);
        EXPECT_LT(m.z / glm::length(m), -0.999) << "moved " << m.x << " " << m.y << " " << m.z;
        // Speed scales with the altitude (thousands of km here): more than a kilometre per frame.
        EXPECT_GT(glm::length(b.offset - a.offset), 1e3);
    }
    // Twist the cap (report 2, rz): the view turns, the position stays.
    mouse.send_report(test::spacemouse_report(1, 0, 0, 0));
    mouse.send_report(test::spacemouse_report(2, 0, 0, 175));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    {
        const auto got = channel.received();
        const auto& a = got[got.size() - 3];
        const auto& b = got[got.size() - 2];
        EXPECT_LT(glm::length(b.offset - a.offset), 1e-3);
        EXPECT_LT(std::abs(glm::dot(a.orientation, b.orientation)), 1.0 - 1e-9);  // turned
    }

    // Unplug while the cap is deflected: the camera stops at once, it does not drift on.
    mouse.send_report(test::spacemouse_report(2, 0, 0, 0));
    mouse.send_report(test::spacemouse_report(1, 175, 0, 0));
    ASSERT_TRUE(channel.wait(now(), moving, std::chrono::seconds(5)));
    bed.unplug(mouse);
    const uint64_t t_unplug = now();
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    const auto got = channel.received();
    size_t after = 0, moved_late = 0;
    for (size_t i = 1; i < got.size(); ++i) {
        if (got[i - 1].ns < t_unplug + 500'000'000ull) continue;  // half a second for the unplug to be seen
        ++after;
        if (moving(got[i - 1], got[i])) ++moved_late;
    }
    EXPECT_GT(after, 20u);
    EXPECT_EQ(moved_late, 0u) << "the camera kept moving after the device was unplugged";
    EXPECT_NE(test::read_text(opt.events_file).find("\"mode\":\"live\""), std::string::npos);  // taken over
}

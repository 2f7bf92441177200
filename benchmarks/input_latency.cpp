// input_latency: how long a navigation device's report takes to leave the master as a snapshot.
//
// Runs under umockdev (`umockdev-wrapper build/bin/input_latency`): an emulated 3Dconnexion
// SpaceNavigator on an emulated USB bus, read by the master's real UsbInput through libusb; a real
// MasterNode (in this process, so it sees the emulated bus) with its frame barrier, director and
// wire; and one channel played at the wire level by this program (hello/welcome handshake, an
// instant FrameDone per snapshot), so the figure is the master's own path, not a renderer's.
//
// Per sample: the cap rests; then, at a random phase of the frame clock, at t0 the device sends "push right" (report 1,
// x = +175 of 350); t1 is when the first snapshot whose camera moved arrives at the channel's socket. Printed: t1 - t0
// (device report to snapshot received, loopback UDP included) and the master's own figure from its events (report
// callback to snapshot sent), at each frame rate asked for.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <thread>

#include "config/cluster_config.hpp"
#include "master_node.hpp"
#include "net/key_file.hpp"
#include "net/wire_endpoint.hpp"
#include "support/umockdev_devices.hpp"
#include "support/wire_channel.hpp"
#include "util/monotonic_clock.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;
using test::Received;
using test::WireChannel;

namespace {

double pct(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<size_t>(p / 100.0 * static_cast<double>(v.size() - 1) + 0.5))];
}

std::string write_config(const std::string& dir, double rate_hz) {
    nlohmann::json c = nlohmann::json::parse(std::ifstream(CUPOLA_SOURCE_DIR "/configs/loopback-1ch.json"));
    for (const char* k : {"key_file", "scene", "show"})
        c[k] = std::string(CUPOLA_SOURCE_DIR "/configs/") + c[k].get<std::string>();
    c["frame_rate_hz"] = rate_hz;
    c["network"]["report_port"] = 47997;
    c["channels"][0]["unicast_address"] = "127.0.0.1:47996";
    c["network"]["channel_timeout_ms"] = 5000;
    c["input"] = {{"usb", true}, {"smoothing_s", 0.0}};  // the pipeline alone; smoothing is a filter on top
    const std::string path = dir + "/cluster.json";
    std::ofstream(path) << c.dump(2);
    return path;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Latency from a USB navigation report to the snapshot leaving the master (run under umockdev-wrapper)"};
    std::vector<double> rates = {60.0, 0.0};
    int samples = 200;
    app.add_option("--rates", rates, "master frame rates to measure (0: as fast as the barrier allows)");
    app.add_option("--samples", samples, "reports per rate")->check(CLI::Range(5, 100000));
    CLI11_PARSE(app, argc, argv);
    spdlog::set_level(spdlog::level::warn);
    if (!test::UsbTestbed::preloaded()) {
        std::fprintf(stderr, "input_latency: run me under umockdev: umockdev-wrapper %s\n", argv[0]);
        return 2;
    }
    const std::string dir = CUPOLA_BENCH_TMP "/input_latency";
    std::filesystem::create_directories(dir);

    test::UsbTestbed bed;
    auto& mouse = bed.add_device(test::space_navigator());
    std::printf(
        "| master frame rate | samples | report → snapshot at the channel: median / p90 / p99 / max (ms) | master's "
        "own report → sent: median / p99 (ms) |\n|---|---|---|---|\n");
    for (double rate : rates) {
        const ClusterConfig cfg = load_cluster_config(write_config(dir, rate));
        const AuthKey key = load_key_file(cfg.key_file, false);
        MasterOptions opt;
        opt.events_file = dir + "/events.jsonl";
        MasterNode master(cfg, opt);
        WireChannel channel(cfg, key);
        std::thread master_thread([&] { master.run(); });
        auto moved = [](const Received& a, const Received& b) { return glm::length(b.offset - a.offset) > 1e-3; };
        auto still = [](const Received&, const Received&) { return true; };
        std::vector<double> ext;
        int missed = 0;
        std::mt19937 rng(7);
        for (int i = 0; i < samples + 3; ++i) {
            mouse.send_report(test::spacemouse_report(1, 0, 0, 0));  // rest
            // Let the rest reach the camera: a few frames without motion.
            for (int k = 0; k < 3; ++k) channel.wait(monotonic_ns(), still, std::chrono::milliseconds(500));
            // At a random phase of the frame clock: a presenter's hand is not synchronised to it.
            if (rate > 0)
                std::this_thread::sleep_for(std::chrono::microseconds(
                    std::uniform_int_distribution<int>(0, static_cast<int>(1e6 / rate))(rng)));
            const uint64_t t0 = monotonic_ns();
            mouse.send_report(test::spacemouse_report(1, 175, 0, 0));
            const auto hit = channel.wait(t0, moved, std::chrono::milliseconds(2000));
            if (!hit) {
                ++missed;
                continue;
            }
            if (i >= 3) ext.push_back(static_cast<double>(hit->ns - t0) / 1e6);  // the first ones warm up (takeover)
        }
        mouse.send_report(test::spacemouse_report(1, 0, 0, 0));
        master.stop();
        master_thread.join();
        std::vector<double> own;
        std::ifstream ev(opt.events_file);
        for (std::string line; std::getline(ev, line);) {
            const auto j = nlohmann::json::parse(line, nullptr, false);
            if (j.is_object() && j.contains("input_latency_ms")) own.push_back(j["input_latency_ms"].get<double>());
        }
        std::printf("| %s | %zu (%d missed) | %.2f / %.2f / %.2f / %.2f | %.2f / %.2f |\n",
                    rate > 0 ? (std::to_string(static_cast<int>(rate)) + " Hz").c_str() : "free (barrier only)",
                    ext.size(), missed, pct(ext, 50), pct(ext, 90), pct(ext, 99), pct(ext, 100), pct(own, 50),
                    pct(own, 99));
        std::fflush(stdout);
    }
    return 0;
}

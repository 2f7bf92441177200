// cupola-loopback: the single-box mode. Starts the master and one slave process per channel on
// this machine, waits for them, then stitches every frame into an angular-fisheye domemaster.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <csignal>
#include <filesystem>
#include <thread>

#include "config/cluster_config.hpp"
#include "dome/domemaster_stitcher.hpp"
#include "image/frame_image.hpp"
#include "util/child_process.hpp"
#include "util/cli_main.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    CLI::App app{"Cupola loopback: master + one slave per channel on this machine, then a stitched domemaster"};
    std::string config, out, control;
    long long frames = 10;
    int size = 0, timeout_s = 600;
    bool verbose = false, no_stitch = false;
    app.add_option("-c,--config", config, "cluster config (JSON)")->required()->check(CLI::ExistingFile);
    auto* frames_opt =
        app.add_option("-n,--frames", frames, "number of frames (default 10; with --control: until quit)")
            ->check(CLI::Range(1LL, 1000000LL));
    app.add_option("--control", control, "the master takes control commands on this local socket (see cupola-control)");
    app.add_option("-o,--out", out, "output folder: <channel>/ frames, dome/ domemasters, logs/")->required();
    app.add_option("--dome-size", size, "domemaster size in pixels (default: from the config)")
        ->check(CLI::Range(16, 16384));
    app.add_option("--timeout", timeout_s, "give up (and stop everything) after this many seconds")
        ->check(CLI::Range(1, 86400));
    app.add_flag("--no-stitch", no_stitch, "only render the channel frames");
    app.add_flag("-v,--verbose", verbose, "debug logging");
    CLI11_PARSE(app, argc, argv);
    cupola::setup_logging("loopback", verbose, false);
    return cupola::run_main("cupola-loopback", [&] {
        const cupola::ClusterConfig cfg = cupola::load_cluster_config(config);
        const std::string bin = cupola::executable_dir();
        fs::create_directories(fs::path(out) / "logs");
        const std::vector<std::string> headless = {"DISPLAY", "WAYLAND_DISPLAY"};

        std::vector<cupola::ChildProcess> slaves;
        for (const auto& ch : cfg.channels) {
            const std::string dir = (fs::path(out) / ch.name).string();
            fs::create_directories(dir);
            std::vector<std::string> args = {bin + "/cupola-slave", "--config", cfg.file, "--channel",
                                             std::to_string(ch.id), "--out",    dir};
            if (verbose) args.push_back("--verbose");
            slaves.emplace_back(args, (fs::path(out) / "logs" / (ch.name + ".log")).string(), headless);
        }
        std::vector<std::string> margs = {bin + "/cupola-master", "--config", cfg.file, "--events",
                                          (fs::path(out) / "logs" / "events.jsonl").string()};
        if (control.empty() || frames_opt->count()) {
            margs.push_back("--frames");
            margs.push_back(std::to_string(frames));
        }
        if (!control.empty()) {
            margs.push_back("--control");
            margs.push_back(control);
        }
        cupola::ChildProcess master(margs, (fs::path(out) / "logs" / "master.log").string(), headless);
        spdlog::info("started master (pid {}) and {} slave(s); logs in {}", master.pid(), slaves.size(),
                     (fs::path(out) / "logs").string());

        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
        auto left = [&] {
            return std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        };
        int failures = 0;
        auto mrc = master.wait_for(left());
        if (!mrc) {
            spdlog::error("master still running after {} s: stopping everything", timeout_s);
            master.kill(SIGTERM);
            master.wait_for(std::chrono::seconds(5));
            return 1;
        }
        if (*mrc != 0) {
            spdlog::error("master exited with code {}; see {}/logs/master.log", *mrc, out);
            ++failures;
        }
        for (size_t i = 0; i < slaves.size(); ++i) {
            auto rc = slaves[i].wait_for(std::max(left(), std::chrono::milliseconds(5000)));
            if (!rc) {
                spdlog::error("slave {} did not quit; killing it", cfg.channels[i].name);
                slaves[i].kill(SIGKILL);
                ++failures;
            } else if (*rc != 0) {
                spdlog::error("slave {} exited with code {}; see {}/logs/{}.log", cfg.channels[i].name, *rc, out,
                              cfg.channels[i].name);
                ++failures;
            }
        }
        if (failures) return 1;
        if (no_stitch) return 0;
        const std::string dome_dir = (fs::path(out) / "dome").string();
        auto report = cupola::stitch_run_directory(cfg, out, dome_dir, std::nullopt, size);
        for (const auto& p : report.problems) spdlog::error("stitch: {}", p);
        if (!report.written.empty())
            spdlog::info("wrote {} domemaster file(s) in {}; last: {}", report.written.size(), dome_dir,
                         report.written.back());
        std::printf("domemaster: %s\n",
                    report.written.empty()
                        ? "(none)"
                        : (dome_dir + "/" + cupola::frame_file_name(report.frames.back(), "png")).c_str());
        return report.problems.empty() && !report.written.empty() ? 0 : 1;
    });
}

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

namespace {

struct LoopbackOptions {
    std::string config, out, control;
    long long frames = 10;
    bool frames_given = false;  // --frames on the command line (with --control: stop after them)
    int size = 0, timeout_s = 600;
    bool verbose = false, no_stitch = false;
};

const std::vector<std::string> kHeadless = {"DISPLAY", "WAYLAND_DISPLAY"};  // unset for the children

// One slave per channel, each writing into <out>/<channel name>/ and logging to logs/.
std::vector<cupola::ChildProcess> start_slaves(const cupola::ClusterConfig& cfg, const LoopbackOptions& opt,
                                               const std::string& bin) {
    std::vector<cupola::ChildProcess> slaves;
    for (const auto& ch : cfg.channels) {
        const std::string dir = (fs::path(opt.out) / ch.name).string();
        fs::create_directories(dir);
        std::vector<std::string> args = {bin + "/cupola-slave", "--config", cfg.file, "--channel",
                                         std::to_string(ch.id), "--out",    dir};
        if (opt.verbose) args.push_back("--verbose");
        slaves.emplace_back(args, (fs::path(opt.out) / "logs" / (ch.name + ".log")).string(), kHeadless);
    }
    return slaves;
}

std::vector<std::string> master_args(const cupola::ClusterConfig& cfg, const LoopbackOptions& opt,
                                     const std::string& bin) {
    std::vector<std::string> margs = {bin + "/cupola-master", "--config", cfg.file, "--events",
                                      (fs::path(opt.out) / "logs" / "events.jsonl").string()};
    if (opt.control.empty() || opt.frames_given) {
        margs.push_back("--frames");
        margs.push_back(std::to_string(opt.frames));
    }
    if (!opt.control.empty()) {
        margs.push_back("--control");
        margs.push_back(opt.control);
    }
    return margs;
}

// Waits for the master, then the slaves, within the timeout; true when all exited with 0.
bool wait_for_cluster(cupola::ChildProcess& master, std::vector<cupola::ChildProcess>& slaves,
                      const cupola::ClusterConfig& cfg, const LoopbackOptions& opt) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(opt.timeout_s);
    auto left = [&] {
        return std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    };
    int failures = 0;
    auto mrc = master.wait_for(left());
    if (!mrc) {
        spdlog::error("master still running after {} s: stopping everything", opt.timeout_s);
        master.kill(SIGTERM);
        master.wait_for(std::chrono::seconds(5));
        return false;
    }
    if (*mrc != 0) {
        spdlog::error("master exited with code {}; see {}/logs/master.log", *mrc, opt.out);
        ++failures;
    }
    for (size_t i = 0; i < slaves.size(); ++i) {
        auto rc = slaves[i].wait_for(std::max(left(), std::chrono::milliseconds(5000)));
        if (!rc) {
            spdlog::error("slave {} did not quit; killing it", cfg.channels[i].name);
            slaves[i].kill(SIGKILL);
            ++failures;
        } else if (*rc != 0) {
            spdlog::error("slave {} exited with code {}; see {}/logs/{}.log", cfg.channels[i].name, *rc, opt.out,
                          cfg.channels[i].name);
            ++failures;
        }
    }
    return failures == 0;
}

// Stitches every frame into <out>/dome/ and prints the last domemaster's path; the exit code.
int stitch(const cupola::ClusterConfig& cfg, const LoopbackOptions& opt) {
    const std::string dome_dir = (fs::path(opt.out) / "dome").string();
    auto report = cupola::stitch_run_directory(cfg, opt.out, dome_dir, std::nullopt, opt.size);
    for (const auto& p : report.problems) spdlog::error("stitch: {}", p);
    if (!report.written.empty())
        spdlog::info("wrote {} domemaster file(s) in {}; last: {}", report.written.size(), dome_dir,
                     report.written.back());
    std::printf("domemaster: %s\n",
                report.written.empty()
                    ? "(none)"
                    : (dome_dir + "/" + cupola::frame_file_name(report.frames.back(), "png")).c_str());
    return report.problems.empty() && !report.written.empty() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Cupola loopback: master + one slave per channel on this machine, then a stitched domemaster"};
    LoopbackOptions opt;
    app.add_option("-c,--config", opt.config, "cluster config (JSON)")->required()->check(CLI::ExistingFile);
    auto* frames_opt =
        app.add_option("-n,--frames", opt.frames, "number of frames (default 10; with --control: until quit)")
            ->check(CLI::Range(1LL, 1000000LL));
    app.add_option("--control", opt.control,
                   "the master takes control commands on this local socket (see cupola-control)");
    app.add_option("-o,--out", opt.out, "output folder: <channel>/ frames, dome/ domemasters, logs/")->required();
    app.add_option("--dome-size", opt.size, "domemaster size in pixels (default: from the config)")
        ->check(CLI::Range(16, 16384));
    app.add_option("--timeout", opt.timeout_s, "give up (and stop everything) after this many seconds")
        ->check(CLI::Range(1, 86400));
    app.add_flag("--no-stitch", opt.no_stitch, "only render the channel frames");
    app.add_flag("-v,--verbose", opt.verbose, "debug logging");
    CLI11_PARSE(app, argc, argv);
    opt.frames_given = frames_opt->count() > 0;
    cupola::setup_logging("loopback", opt.verbose, false);
    return cupola::run_main("cupola-loopback", [&] {
        const cupola::ClusterConfig cfg = cupola::load_cluster_config(opt.config);
        const std::string bin = cupola::executable_dir();
        fs::create_directories(fs::path(opt.out) / "logs");
        std::vector<cupola::ChildProcess> slaves = start_slaves(cfg, opt, bin);
        cupola::ChildProcess master(master_args(cfg, opt, bin), (fs::path(opt.out) / "logs" / "master.log").string(),
                                    kHeadless);
        spdlog::info("started master (pid {}) and {} slave(s); logs in {}", master.pid(), slaves.size(),
                     (fs::path(opt.out) / "logs").string());
        if (!wait_for_cluster(master, slaves, cfg, opt)) return 1;
        if (opt.no_stitch) return 0;
        return stitch(cfg, opt);
    });
}

// cupola-master: owns time, camera and bodies; broadcasts a snapshot per frame; runs the barrier.
#include <CLI/CLI.hpp>

#include <csignal>

#include "config/cluster_config.hpp"
#include "master_node.hpp"
#include "util/cli_main.hpp"

namespace {
cupola::MasterNode* g_master = nullptr;
void on_signal(int) {
    if (g_master) g_master->stop();
}
}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Cupola master: simulation owner and frame-barrier for the cluster"};
    std::string config;
    long long frames = -1;
    std::string events, stats, control;
    bool verbose = false, quiet = false, no_resume = false;
    app.add_option("-c,--config", config, "cluster config (JSON)")->required()->check(CLI::ExistingFile);
    app.add_option("-n,--frames", frames,
                   "stop before frame N (frames 0..N-1, a resumed show included) and tell the slaves to quit")
        ->check(CLI::Range(1LL, 1LL << 40));
    app.add_option("--events", events, "write per-frame and per-channel events as JSON lines to this file");
    app.add_option("--stats", stats, "keep the anomaly counters in this JSON file (rewritten every second)");
    app.add_option(
        "--control", control,
        "take control commands (goto, time rate, play, quit...) on this local socket, or - for standard input");
    app.add_flag("--no-resume", no_resume, "start at frame 0 even when the slaves already rendered frames");
    app.add_flag("-v,--verbose", verbose, "debug logging");
    app.add_flag("-q,--quiet", quiet, "warnings and errors only");
    CLI11_PARSE(app, argc, argv);
    cupola::setup_logging("master", verbose, quiet);
    return cupola::run_main("cupola-master", [&] {
        cupola::MasterOptions opt;
        if (frames > 0) opt.frames = static_cast<uint64_t>(frames);
        opt.events_file = events;
        opt.stats_file = stats;
        opt.resume = !no_resume;
        opt.control = control;
        cupola::MasterNode master(cupola::load_cluster_config(config), opt);
        g_master = &master;
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        std::signal(SIGPIPE, SIG_IGN);  // a control client that went away is an error return, not a kill
        return master.run();
    });
}

// cupola-slave: one process per channel; renders its frustum slice headlessly through EGL.
#include <CLI/CLI.hpp>

#include <csignal>

#include "config/cluster_config.hpp"
#include "slave_node.hpp"
#include "util/cli_main.hpp"

namespace {
cupola::SlaveNode* g_slave = nullptr;
void on_signal(int) {
    if (g_slave) g_slave->stop();
}
}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Cupola slave: renders one channel of the dome headlessly (EGL, no display server)"};
    std::string config, channel, out, stats, present_log;
    int egl_device = -2, idle_timeout = 30;
    std::vector<std::string> formats;
    bool verbose = false, quiet = false;
    app.add_option("-c,--config", config, "cluster config (JSON)")->required()->check(CLI::ExistingFile);
    app.add_option("--channel", channel, "channel id or name from the config")->required();
    app.add_option("-o,--out", out, "folder for this channel's frame files")->required();
    app.add_option("--egl-device", egl_device, "EGL device index (-1: first usable, then Mesa surfaceless)")
        ->check(CLI::Range(-1, 64));
    app.add_option("--formats", formats, "png and/or exr (default: from the config)")
        ->check(CLI::IsMember({"png", "exr"}))
        ->delimiter(',');
    app.add_option("--idle-timeout", idle_timeout, "exit when no snapshot arrives for this many seconds")
        ->check(CLI::Range(1, 86400));
    app.add_option("--stats", stats, "keep the anomaly counters in this JSON file (rewritten every second)");
    app.add_option("--present-log", present_log,
                   "write one JSON line per frame shown (frame, ready_ns, present_ns: CLOCK_MONOTONIC)");
    app.add_flag("-v,--verbose", verbose, "debug logging");
    app.add_flag("-q,--quiet", quiet, "warnings and errors only");
    CLI11_PARSE(app, argc, argv);
    cupola::setup_logging("slave-" + channel, verbose, quiet);
    return cupola::run_main("cupola-slave", [&] {
        cupola::ClusterConfig cfg = cupola::load_cluster_config(config);
        int id = -1;
        for (const auto& c : cfg.channels)
            if (c.name == channel || std::to_string(c.id) == channel) id = c.id;
        if (id < 0) throw std::invalid_argument("--channel " + channel + ": no such channel id or name in " + config);
        cupola::SlaveOptions opt;
        opt.out_dir = out;
        opt.egl_device = egl_device;
        opt.idle_timeout_s = idle_timeout;
        opt.formats = formats;
        opt.stats_file = stats;
        opt.present_log = present_log;
        cupola::SlaveNode slave(std::move(cfg), id, opt);
        g_slave = &slave;
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        return slave.run();
    });
}

// Benchmark (not a test): the 4-channel cluster across network namespaces (master host, three
// slave hosts; tests/support/netns_cluster.hpp) at several loss levels injected with nftables.
// Prints dome frames/s, the barrier's overhead per frame (the master's frame time minus the
// slowest channel's render + write), and the snapshot latency from the master's send to the
// slave's complete reception (CLOCK_MONOTONIC, comparable across namespaces on one host): median
// and p99 over all channel-frames, resends included. Needs root (network namespaces).
//   build/bin/cluster_network [--frames 600] [--size 64] [--loss 0,1,5]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>

#include "support/netns_cluster.hpp"

using namespace cupola;

namespace {

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Cupola cluster over network namespaces: frames/s, barrier overhead, snapshot latency vs loss"};
    int frames = 600, size = 64;
    std::vector<double> losses = {0, 1, 5};
    app.add_option("--frames", frames)->check(CLI::Range(10, 100000));
    app.add_option("--size", size, "channel width and height in pixels")->check(CLI::Range(8, 4096));
    app.add_option("--loss", losses, "loss levels in percent")->delimiter(',');
    CLI11_PARSE(app, argc, argv);
    const std::string why = test::NetnsTestbed::unavailable_reason();
    if (!why.empty()) {
        std::fprintf(stderr, "cluster_network: needs network namespaces: %s\n", why.c_str());
        return 2;
    }
    std::printf(
        "| loss | frames/s | frame ms (median) | barrier overhead ms (median / p99) | snapshot latency ms (median / "
        "p99) | resends/frame |\n");
    std::printf("|---|---|---|---|---|---|\n");
    for (double loss : losses) {
        test::NetnsClusterOptions o;
        o.width = o.height = size;
        test::NetnsCluster c("bench" + std::to_string(static_cast<int>(loss * 10)), o);
        for (const char* h : {"s1", "s2", "s3"})
            c.bed.set_loss(h, loss, test::NetnsCluster::kSnapshotPort, test::NetnsCluster::kSnapshotPort);
        c.bed.set_loss("master", loss, test::NetnsCluster::kReportPort, test::NetnsCluster::kReportPort);
        c.start_all(frames);
        std::string failures;
        c.finish(failures, std::chrono::seconds(3600));
        if (!failures.empty()) {
            std::fprintf(stderr, "%s\n", failures.c_str());
            return 1;
        }
        std::vector<double> frame_ms, overhead_ms, latency_ms;
        double seconds = 0;
        for (const auto& e : test::read_events(c.dir + "/master.events.jsonl")) {
            const std::string kind = e.value("event", "");
            if (kind == "end") seconds = e["seconds"].get<double>();
            if (kind != "frame") continue;
            const double f = e["frame_ms"].get<double>();
            double slowest = 0;
            for (const auto& [id, ch] : e["channels"].items()) {
                slowest = std::max(slowest, ch["render_ms"].get<double>() + ch["write_ms"].get<double>());
                latency_ms.push_back(ch["latency_ms"].get<double>());
            }
            frame_ms.push_back(f);
            overhead_ms.push_back(std::max(0.0, f - slowest));
        }
        const auto m = c.stats(c.master_stats());
        std::printf("| %.0f %% | %.1f | %.2f | %.2f / %.2f | %.3f / %.2f | %.3f |\n", loss, frame_ms.size() / seconds,
                    percentile(frame_ms, 0.5), percentile(overhead_ms, 0.5), percentile(overhead_ms, 0.99),
                    percentile(latency_ms, 0.5), percentile(latency_ms, 0.99),
                    m["master"]["snapshot_resends"].get<double>() / frame_ms.size());
        std::fflush(stdout);
    }
    return 0;
}

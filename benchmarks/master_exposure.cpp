// The master's exposure per frame (common/atmosphere/auto_exposure + common/exposure/): the
// metering of grid x grid rays per channel through every atmosphere, the statistics, the
// adaptation step. It runs on the master's CPU once per frame, so its time is a share of the
// frame budget (16.7 ms at 60 Hz), reported as `budget_share`. Its error: the metered
// log-average and highlight against a 64 x 64 grid of the same view (`log_avg_err`,
// `highlight_err`, relative), so that the grid's speed can be weighed against its error.
//   build/bin/master_exposure --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <string>

#include "atmosphere/auto_exposure.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "director.hpp"
#include "master_node.hpp"
#include "show_script.hpp"

using namespace cupola;

namespace {

constexpr double kFrameBudget_s = 1.0 / 60.0;

struct View {
    ClusterConfig cluster;
    SceneConfig scene;
    Snapshot snap;
    double interval_s = 0.0;
};

// view: 0 = the descent show (1 channel) from orbit, 1 = its sunset, 2 = the 2006 eclipse on a
// 4-channel dome at greatest eclipse.
View view_of(int64_t view) {
    View v;
    v.cluster = load_cluster_config(std::string(CUPOLA_SOURCE_DIR) +
                                    (view == 2 ? "/configs/eclipse-2006-dome.json" : "/configs/descent-1ch.json"));
    v.scene = load_scene_config(v.cluster.scene_file);
    const ShowScript show = ShowScript::load(v.cluster.show_file, v.scene);
    v.snap = make_frame_snapshot(v.cluster, v.scene, show, view == 1 ? 28 : 0);
    v.interval_s = show_frame_interval_s(v.cluster, show);
    return v;
}

// args: the view, the metering grid.
void BM_ExposureDecision(benchmark::State& state) {
    const View v = view_of(state.range(0));
    const int grid = static_cast<int>(state.range(1));
    const AutoExposure exposure(v.cluster, v.scene);
    EyeAdaptation eye;
    for (auto _ : state) {
        const SkyMetering m = exposure.meter(v.snap, grid);
        benchmark::DoNotOptimize(
            decide_exposure(m, eye.step(adaptation_target(m), v.interval_s, v.cluster.output.auto_exposure),
                            v.cluster.output.auto_exposure));
    }
    const SkyMetering m = exposure.meter(v.snap, grid), reference = exposure.meter(v.snap, 64);
    state.counters["channels"] = static_cast<double>(v.cluster.channels.size());
    state.counters["log_avg_err"] = m.log_average / reference.log_average - 1.0;
    state.counters["highlight_err"] = m.highlight / reference.highlight - 1.0;
    state.counters["budget_share"] =
        benchmark::Counter(kFrameBudget_s, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_ExposureDecision)
    ->ArgsProduct({{0, 1, 2}, {4, 8, 16}})
    ->ArgNames({"view", "grid"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

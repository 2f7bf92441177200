// The terrain's CPU side against its error budget: for each budget, the tiles and triangles the
// cluster-wide cut selects for the 4-channel dome, the time to choose the cut (cold: no tile
// height ranges cached; warm: the next frame of a slow descent, the cache kept) and to build the
// cut's meshes on one thread, without and with the horizon map the drawn tiles carry. The GPU's time for the triangles
// is not measured here (the tiles are not drawn yet). CPU times are absolute (nothing to take a ratio to on the CPU),
// medians.
//   terrain_cut_cost [--budgets 0.5,1,2,4] [--height-m 1500] [--segments 32] [--frames 5]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <glm/gtc/quaternion.hpp>

#include "config/cluster_config.hpp"
#include "terrain/cluster_cut_view.hpp"
#include "terrain/terrain_cut.hpp"
#include "terrain/tile_mesh.hpp"

using namespace cupola;
using namespace cupola::terrain;

namespace {
constexpr double kDeg = 0.017453292519943295769;
constexpr double kEarth_m = 6371e3;

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The camera height_m above (46.5 N, 10 E), looking south 20 degrees down.
CutView view_at(const ClusterConfig& cluster, double height_m) {
    const glm::dvec3 up = lat_lon_to_direction(46.5 * kDeg, 10.0 * kDeg);
    const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), up)), north = glm::cross(up, east);
    const double p = -20.0 * kDeg;
    const glm::dvec3 forward = std::cos(p) * -north + std::sin(p) * up;
    const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
    const glm::dquat q = glm::quat_cast(glm::dmat3(right, glm::cross(right, forward), -forward));
    return cut_view_for_cluster(cluster, up * (kEarth_m + height_m), glm::dmat3(1.0), q);
}

void run_budget(const ClusterConfig& cluster, const Relief& relief, double budget, double height_m, int segments,
                int frames) {
    CutSettings s;
    s.budget_px = budget;
    s.segments = segments;
    s.max_tiles = 20000;
    TileRangeCache ranges;
    auto t0 = std::chrono::steady_clock::now();
    TerrainCut cut = select_cut(relief, view_at(cluster, height_m), s, ranges);
    const double cold_ms = ms_since(t0);
    std::vector<double> warm;
    for (int f = 1; f <= frames; ++f) {  // descending 0.5 % a frame
        t0 = std::chrono::steady_clock::now();
        cut = select_cut(relief, view_at(cluster, height_m * (1.0 - 0.005 * f)), s, ranges);
        warm.push_back(ms_since(t0));
    }
    t0 = std::chrono::steady_clock::now();
    const size_t sample = std::min<size_t>(cut.tiles.size(), 200);
    for (size_t i = 0; i < sample; ++i) build_tile_mesh(cut.tiles[i * cut.tiles.size() / sample].key, relief, segments);
    const double build_ms = ms_since(t0) / static_cast<double>(sample);
    t0 = std::chrono::steady_clock::now();  // with the horizon map (the relief's shadows), as drawn
    const size_t shadowed = std::min<size_t>(sample, 50);
    for (size_t i = 0; i < shadowed; ++i)
        build_tile_mesh(cut.tiles[i * cut.tiles.size() / shadowed].key, relief, segments, true);
    const double horizon_ms = ms_since(t0) / static_cast<double>(shadowed);
    const size_t triangles = cut.tiles.size() * (2u * segments * segments + 8u * segments);
    std::printf("| %.1f | %zu | %.2f M | %.0f | %.1f | %.2f | %.2f | %.2f | %s |\n", budget, cut.tiles.size(),
                triangles / 1e6, cold_ms, median(warm), build_ms, horizon_ms, build_ms * cut.tiles.size() / 1000.0,
                cut.capped ? "yes" : "no");
}
}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"The terrain cut's tiles, triangles and CPU time against the error budget"};
    std::vector<double> budgets{0.5, 1.0, 2.0, 4.0};
    double height_m = 1500.0;
    int segments = 32, frames = 5;
    app.add_option("--budgets", budgets, "error budgets in pixels")->delimiter(',');
    app.add_option("--height-m", height_m, "camera height above the reference sphere")->check(CLI::Range(1.0, 1e8));
    app.add_option("--segments", segments, "quads along a tile side (even)")->check(CLI::Range(2, 256));
    app.add_option("--frames", frames, "warm frames per budget")->check(CLI::Range(1, 1000));
    CLI11_PARSE(app, argc, argv);
    const ClusterConfig cluster = load_cluster_config(CUPOLA_SOURCE_DIR "/configs/dome-4ch.json");
    ProceduralRelief p;
    p.base_wavelength_m = 100e3;
    p.base_amplitude_m = 1200.0;
    p.gain = 0.55;
    const Relief relief(kEarth_m, nullptr, p);
    std::printf("terrain_cut_cost: dome-4ch, %.0f m up, %d segments, procedural relief\n", height_m, segments);
    std::printf(
        "| budget px | tiles | triangles | cut cold ms | cut warm ms (median) | mesh ms/tile | with horizon "
        "ms/tile | all meshes s (1 thread, no horizon) | capped |\n|---|---|---|---|---|---|---|---|---|\n");
    for (double b : budgets) run_budget(cluster, relief, b, height_m, segments, frames);
    return 0;
}

// Speed against error of every production atmosphere model.
//   atmosphere_speed_vs_error [--size N] [--frames N] [--csv FILE]
// For each quality level: table build time and memory (no cache), the error against the stored
// reference dataset (data/atmosphere/earth_reference.csv, see production_accuracy.hpp), and the
// time per frame of a full channel render at N x N (default 1024) through EGL with and without the
// atmosphere, from the ground looking at the horizon with the Sun 65 degrees from the zenith.
// Prints a Markdown table; --csv also writes the figures for tools/plot_speed_vs_error.py.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "atmosphere/production_accuracy.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "scene_renderer.hpp"

using namespace cupola;
namespace at = cupola::atmosphere;
namespace fs = std::filesystem;

namespace {

struct Row {
    std::string level;
    double build_s = 0, table_kib = 0;
    at::AccuracyReport accuracy;
    double ms_frame = 0, ms_pass = 0;
    bool pareto = false;
};

// A ground camera 2 m above the Earth looking at the horizon, the Sun 65 deg from the zenith.
Snapshot ground_view(const SceneConfig& scene) {
    Snapshot s;
    s.bodies.resize(scene.bodies.size());
    for (auto& b : s.bodies) b.id = static_cast<uint16_t>(&b - s.bodies.data());
    const uint16_t sun = scene.find("sun")->id, earth = scene.find("earth")->id;
    const double R = scene.bodies[earth].radius_m;
    const glm::dvec3 up(0, 0, 1), north(0, 1, 0), east(1, 0, 0);
    const double z = glm::radians(65.0);
    s.bodies[earth].position_m = glm::dvec3(0.0);
    s.bodies[sun].position_m = 1.496e11 * (std::cos(z) * up + std::sin(z) * north);
    if (auto* moon = scene.find("moon")) s.bodies[moon->id].position_m = glm::dvec3(0, -3.844e8, 0);
    s.camera_position_m = (R + 2.0) * up;
    // Camera frame columns: +X right (east), +Y up, +Z back (south): looking north, at the Sun's azimuth.
    s.camera_orientation = glm::quat_cast(glm::dmat3(east, up, -north));
    return s;
}

double render_ms(const ClusterConfig& cluster, const ChannelConfig& ch, const SceneConfig& scene, int frames) {
    SceneRenderer r(cluster, ch, scene);
    const Snapshot s = ground_view(scene);
    r.render(s);  // warm-up: shader compilation, first upload
    std::vector<double> ms;
    for (int i = 0; i < frames; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        r.render(s);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"atmosphere speed vs error"};
    int size = 1024, frames = 5;
    std::string csv, source = CUPOLA_SOURCE_DIR;
    app.add_option("--size", size, "channel width and height in pixels");
    app.add_option("--frames", frames, "timed frames per level (median reported)");
    app.add_option("--csv", csv, "also write the figures as CSV");
    CLI11_PARSE(app, argc, argv);
    spdlog::set_level(spdlog::level::warn);
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    const std::string cache = (fs::temp_directory_path() / "cupola-bench-cache").string();
    fs::remove_all(cache);
    setenv("CUPOLA_CACHE_DIR", cache.c_str(), 1);

    const at::ReferenceDataset ref = at::read_reference_dataset(source + "/data/atmosphere/earth_reference.csv");
    EglContext gl(-1);
    std::printf("renderer: %s\n", gl.info().renderer.c_str());
    ClusterConfig cluster;
    ChannelConfig ch;
    ch.id = 0;
    ch.name = "bench";
    ch.fov = {45.0, 45.0, 45.0, 45.0};
    ch.width = ch.height = size;
    cluster.channels.push_back(ch);

    nlohmann::json scene_json = nlohmann::json::parse(std::ifstream(source + "/configs/scenes/earth-physical.json"));
    scene_json["stars"]["catalog"] = source + "/data/stars/bright_stars.csv";
    const fs::path scene_file = fs::temp_directory_path() / "cupola-bench-scene.json";
    auto scene_with = [&](const std::string& level) {
        nlohmann::json j = scene_json;
        for (auto& b : j["bodies"]) {
            if (b["name"] == "earth" && !level.empty()) b["atmosphere"]["model"] = level;
            if (b["name"] == "earth" && level.empty()) b.erase("atmosphere");
            if (b.contains("texture") && b["texture"].get<std::string>().rfind("generated:", 0) != 0)
                b["texture"] = "generated:" + b["name"].get<std::string>();
        }
        std::ofstream(scene_file) << j.dump(2);
        return load_scene_config(scene_file.string());
    };

    const double base_ms = render_ms(cluster, ch, scene_with(""), frames);
    std::vector<Row> rows;
    for (const std::string& level : at::production_quality_names()) {
        Row row;
        row.level = level;
        at::TableCacheOptions no_cache;
        no_cache.enabled = false;
        const at::ProductionAtmosphere model(at::AtmosphereParameters::earth(), at::production_quality(level),
                                             no_cache);
        row.build_s = model.tables().build_seconds;
        row.table_kib = model.tables().bytes() / 1024.0;
        row.accuracy = at::measure_accuracy(model, ref);
        row.ms_frame = render_ms(cluster, ch, scene_with(level), frames);
        row.ms_pass = row.ms_frame - base_ms;
        rows.push_back(row);
        std::fprintf(stderr, "%s done\n", level.c_str());
    }
    for (auto& a : rows) {
        a.pareto = true;
        for (const auto& b : rows)
            if (&a != &b && b.ms_frame <= a.ms_frame && b.accuracy.overall.median <= a.accuracy.overall.median &&
                (b.ms_frame < a.ms_frame || b.accuracy.overall.median < a.accuracy.overall.median))
                a.pareto = false;
    }
    std::printf("\nframe without atmosphere: %.1f ms at %dx%d\n\n", base_ms, size, size);
    std::printf(
        "| model | ms/frame | atmosphere pass ms | table build s | tables KiB | median err | p99 err | median du'v' | "
        "Pareto |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& r : rows)
        std::printf("| %s%s | %.1f | %.1f | %.3f | %.0f | %.2f %% | %.1f %% | %.4f | %s |\n", r.level.c_str(),
                    r.level == at::kDefaultProductionQuality ? " (default)" : "", r.ms_frame, r.ms_pass, r.build_s,
                    r.table_kib, 100 * r.accuracy.overall.median, 100 * r.accuracy.overall.p99,
                    r.accuracy.overall.chroma_median, r.pareto ? "yes" : "no");
    if (!csv.empty()) {
        std::ofstream out(csv);
        out << "model,ms_frame,ms_pass,build_s,table_kib,median,p99,chroma_median,pareto,default\n";
        for (const auto& r : rows)
            out << r.level << "," << r.ms_frame << "," << r.ms_pass << "," << r.build_s << "," << r.table_kib << ","
                << r.accuracy.overall.median << "," << r.accuracy.overall.p99 << "," << r.accuracy.overall.chroma_median
                << "," << (r.pareto ? 1 : 0) << "," << (r.level == at::kDefaultProductionQuality ? 1 : 0) << "\n";
    }
    for (const auto& r : rows)
        if (r.level == at::kDefaultProductionQuality && !r.pareto) {
            std::printf("\nWARNING: the default model is not on the Pareto front\n");
            return 1;
        }
    return 0;
}

// Glare cost and visibility accuracy per channel: one channel looking at the Sun half
// hidden behind the Moon, rendered by the real SceneRenderer (EGL, the slave's passes), with the
// glare off and with the glare on at several probe sizes. For each: ms per frame, the extra cost
// of the glare (probe + occlusion queries + glare pass), and the visible fraction the queries
// measured against the analytic one (common/glare/analytic_visibility, the same eclipse math).
//   build/bin/glare_cost [--size 512] [--frames 20]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <memory>
#include <cmath>
#include <cstdio>

#include "glare/glare_sources.hpp"
#include "show_script.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "glare/analytic_visibility.hpp"
#include "scene_renderer.hpp"
#include "util/cli_parse.hpp"

using namespace cupola;

namespace {

glm::dvec3 position_of(const Snapshot& s, uint16_t id) {
    for (const auto& b : s.bodies)
        if (b.id == id) return b.position_m;
    return {};
}

double time_frames(SceneRenderer& r, const Snapshot& snap, int frames) {
    for (int i = 0; i < 2; ++i) r.render(snap);  // warm-up (shader compile, first upload)
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) r.render(snap);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / frames;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Glare cost (ms per frame per channel) and visibility accuracy against the probe size"};
    int size = 512, frames = 20;
    std::string scene_file = "configs/scenes/earth-moon.json";
    app.add_option("--size", size, "channel width and height in pixels")->check(CLI::Range(16, 8192));
    app.add_option("--frames", frames, "timed frames per case")->check(CLI::Range(1, 100000));
    app.add_option("--scene", scene_file, "scene (its atmospheres are dropped: space view)")->check(CLI::ExistingFile);
    if (auto rc = parse_command_line(app, argc, argv, "glare_cost")) return *rc;

    SceneConfig scene = load_scene_config(scene_file);
    for (auto& b : scene.bodies) {
        b.atmosphere.present = false;
        if (b.kind != BodyKind::Star) b.texture = "generated:" + b.name;
    }
    const uint16_t sun = scene.find("sun")->id, moon = scene.find("moon")->id;
    // The Sun's centre on the Moon's limb, seen from 40 lunar radii.
    ShowKeyframe k;
    k.sim_time_s = 765806400.0;  // 2024-04-08 12:00 TT
    k.camera.anchor = moon;
    k.camera.look_at = sun;
    Snapshot snap = ShowScript({k}, 1.0).evaluate(0.0, scene);
    const glm::dvec3 u = glm::normalize(position_of(snap, sun) - position_of(snap, moon));
    const glm::dvec3 w = glm::normalize(glm::cross(u, glm::dvec3(0, 0, 1)));
    const double rm = scene.bodies[moon].radius_m;
    k.camera.offset_m = -40.0 * rm * u + rm * w;
    snap = ShowScript({k}, 1.0).evaluate(0.0, scene);
    snap.settings.exposure = 0.5f;
    scene.glare.enabled = true;
    snap.glare = GlareSources(scene, nullptr).select(snap);
    const GlareVisibility analytic =
        analytic_visibility(snap.camera_position_m, position_of(snap, sun), scene.bodies[sun].radius_m,
                            snapshot_occluders(snap, scene, sun));

    ClusterConfig cluster;
    ChannelConfig ch;
    ch.name = "front";
    ch.fov = FovDeg{45, 45, 45, 45};
    ch.width = ch.height = size;
    cluster.channels = {ch};

    EglContext gl(-1);
    std::printf("renderer: %s; channel %dx%d (90 degrees), %d frames per case\n", gl.info().renderer.c_str(), size,
                size, frames);
    std::printf("analytic visible fraction %.5f\n\n", analytic.visible_fraction);
    // Every case is built first, then timed in interleaved rounds (the median of 5 is kept), so
    // that drifts of the machine hit every case alike.
    std::vector<int> probes = {0, 16, 32, 64, 128};  // 0: glare off
    std::vector<std::unique_ptr<SceneRenderer>> renderers;
    std::vector<SceneConfig> scenes;
    for (int probe : probes) {
        SceneConfig s = scene;
        s.glare.enabled = probe > 0;
        if (probe > 0) s.glare.probe_size = probe;
        scenes.push_back(s);
    }
    for (size_t i = 0; i < probes.size(); ++i)
        renderers.push_back(std::make_unique<SceneRenderer>(cluster, ch, scenes[i]));
    std::vector<std::vector<double>> ms(probes.size());
    for (int round = 0; round < 5; ++round)
        for (size_t i = 0; i < probes.size(); ++i) ms[i].push_back(time_frames(*renderers[i], snap, frames));
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    const double base = median(ms[0]);
    std::printf("| glare | probe | ms/frame | glare ms/frame | measured fraction | error |\n");
    std::printf("|---|---|---|---|---|---|\n");
    std::printf("| off | - | %.2f | - | - | - |\n", base);
    for (size_t i = 1; i < probes.size(); ++i) {
        double total = 0.0, seen = 0.0;
        for (const auto& m : renderers[i]->glare_measurements())
            if (m.body == sun) total += m.total_sr, seen += m.visible_total_sr();
        const double f = total > 0.0 ? seen / total : -1.0;
        const double t = median(ms[i]);
        std::printf("| on | %d | %.2f | %.2f | %.5f | %+.2f %% |\n", probes[i], t, t - base, f,
                    100.0 * (f / analytic.visible_fraction - 1.0));
    }
    return 0;
}

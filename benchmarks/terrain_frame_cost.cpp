// Terrain frame cost: the earth-moon scene's Earth as procedural relief (slave/passes/
// terrain_drawer.cpp), one channel 1.5 km above the ground in the evening, rendered by the real
// SceneRenderer (EGL, the slave's passes). Per error budget (0.5, 1, 2, 4 px): the cut's tiles and
// the triangles drawn, ms per frame, and the frame and its terrain's extra (the frame minus the
// smooth sphere's) as ratios to a trivial full-screen pass (one texel copied per pixel into an
// RGBA32F target of the channel's size) timed in the same run.
// Streaming: a descent of `--path` frames whose tiles are built by a fast source, then by a slow
// one (every tile build sleeps --slow-ms first, as a slow disk would): the render loop's frame
// times (median and 90th percentile) must not follow the source, and the frames that drew
// stand-ins are counted.
// With --glare the camera looks west at the Sun and the snapshot carries its glare sources (as the
// master selects them), so the glare probe runs; its pass, timed with a wait after it, is given per case (the relief
// hides the Sun from the probe as it hides it in the frame: TerrainDrawer::draw_depth).
//   build/bin/terrain_frame_cost [--size 256] [--frames 5] [--path 40] [--slow-ms 20] [--glare]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <thread>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "glare/glare_sources.hpp"
#include "passes/terrain_drawer.hpp"
#include "scene_renderer.hpp"
#include "terrain/cube_sphere.hpp"
#include "terrain/terrain_clearance.hpp"
#include "util/cli_parse.hpp"

using namespace cupola;

namespace {

double ms_of(const std::function<void()>& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

// The glare probe's pass (ms, with a wait after it), the median of five frames; 0 without one.
double probe_ms(SceneRenderer& r, const Snapshot& snap) {
    std::vector<double> t;
    r.set_pass_timing(true);
    for (int i = 0; i < 5; ++i) {
        r.render(snap);
        for (const auto& [name, ms] : r.last_frame_timings().passes_ms)
            if (name == "glare probe") t.push_back(ms);
    }
    r.set_pass_timing(false);
    return t.empty() ? 0.0 : percentile(t, 0.5);
}

SceneConfig scene_with_terrain(const std::string& file, bool terrain, double budget_px) {
    SceneConfig s = load_scene_config(file);
    for (auto& b : s.bodies) {
        b.texture = "generated:" + b.name;
        if (b.name != "earth") continue;
        b.terrain.present = terrain;
        b.terrain.error_budget_px = budget_px;
        b.terrain.procedural_wavelength_m = 60e3;
        b.terrain.procedural_amplitude_m = 1600.0;
        b.terrain.seed = 7;
    }
    return s;
}

// The camera height_m above the ground at (46 N, 7.7 E) looking north-west and 10 degrees down
// (toward_sun: west, toward the Sun, and 6 degrees down), the Sun 8 degrees up in the west.
Snapshot evening_view(const SceneConfig& s, double height_m, bool toward_sun = false) {
    Snapshot snap;
    snap.bodies.resize(s.bodies.size());
    for (auto& b : snap.bodies) b.id = static_cast<uint16_t>(&b - snap.bodies.data());
    const double deg = 0.017453292519943295769;
    const glm::dvec3 up = terrain::lat_lon_to_direction(46.0 * deg, 7.7 * deg);
    const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), up)), north = glm::cross(up, east);
    const terrain::TerrainClearance ground(s);
    BodyState earth;
    earth.id = s.find("earth")->id;
    const double r = s.find("earth")->radius_m;
    snap.camera_position_m = up * (r + ground.ground_height_m(earth, up * r) + height_m);
    snap.bodies[s.find("sun")->id].position_m = 1.495978707e11 * glm::normalize(-east + 0.14 * up);
    snap.bodies[s.find("moon")->id].position_m = 3.844e8 * glm::normalize(east - 0.3 * up);
    const glm::dvec3 fwd = toward_sun ? glm::normalize(-east - 0.1 * up) : glm::normalize(north - east - 0.25 * up);
    const glm::dvec3 right = glm::normalize(glm::cross(fwd, up));
    snap.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(right, fwd), -fwd));
    return snap;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Terrain cost: triangles and ms per frame per error budget, ratios to a trivial pass; streaming"};
    int size = 256, frames = 5, path = 40, slow_ms = 20;
    std::string scene_file = "configs/scenes/earth-moon.json";
    app.add_option("--size", size, "channel width and height in pixels")->check(CLI::Range(16, 8192));
    app.add_option("--frames", frames, "timed frames per case and round")->check(CLI::Range(1, 100000));
    app.add_option("--path", path, "frames of the streaming descent")->check(CLI::Range(4, 100000));
    app.add_option("--slow-ms", slow_ms, "the slow source's delay per tile")->check(CLI::Range(1, 10000));
    app.add_option("--scene", scene_file, "scene with an 'earth'")->check(CLI::ExistingFile);
    bool glare = false;
    app.add_flag("--glare", glare, "the snapshot carries its glare sources: the glare probe runs (timed)");
    if (auto rc = parse_command_line(app, argc, argv, "terrain_frame_cost")) return *rc;
    ClusterConfig cluster;
    ChannelConfig ch;
    ch.name = "front";
    ch.fov = FovDeg{45, 45, 45, 45};
    ch.width = ch.height = size;
    cluster.channels = {ch};
    EglContext gl(-1);
    std::printf("renderer: %s; channel %dx%d (90 degrees), 1.5 km above the ground\n\n", gl.info().renderer.c_str(),
                size, size);

    GlFramebuffer trivial_target(size, size);
    const std::vector<glm::vec4> texels(static_cast<size_t>(size) * size, glm::vec4(0.5f));
    GlTexture source(size, size, texels.data(), GL_NEAREST);
    GlProgram trivial("fullscreen.vert", "fullscreen_copy.frag");
    GlEmptyVertexArray triangle;
    const auto trivial_pass = [&] {
        trivial_target.bind();
        trivial.use();
        source.bind(0);
        trivial.set("u_source", 0);
        triangle.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    const std::vector<double> budgets = {0.0, 0.5, 1.0, 2.0, 4.0};  // 0: the smooth sphere
    std::vector<std::unique_ptr<SceneRenderer>> renderers;
    std::vector<SceneConfig> scenes;
    for (double b : budgets) scenes.push_back(scene_with_terrain(scene_file, b > 0.0, b > 0.0 ? b : 1.0));
    Snapshot snap = evening_view(scenes[1], 1500.0, glare);
    if (glare) snap.glare = GlareSources(scenes[1], nullptr).select(snap);
    for (const SceneConfig& s : scenes) {
        renderers.push_back(std::make_unique<SceneRenderer>(cluster, ch, s));
        renderers.back()->render(snap);
        if (s.find("earth")->terrain.present) renderers.back()->terrain().wait_idle();
        renderers.back()->render(snap);
    }
    // Interleaved rounds, the median of 5 kept per case.
    std::vector<std::vector<double>> ms(budgets.size() + 1);
    for (int round = 0; round < 5; ++round) {
        ms[0].push_back(ms_of([&] {
                            for (int i = 0; i < frames; ++i) trivial_pass();
                        }) /
                        frames);
        for (size_t i = 0; i < renderers.size(); ++i)
            ms[i + 1].push_back(ms_of([&] {
                                    for (int f = 0; f < frames; ++f) renderers[i]->render(snap);
                                }) /
                                frames);
    }
    const double t_trivial = percentile(ms[0], 0.5), t_smooth = percentile(ms[1], 0.5);
    std::printf("trivial full-screen pass %.3f ms; frame with the smooth sphere %.2f ms (%.1f trivial passes)\n",
                t_trivial, t_smooth, t_smooth / t_trivial);
    if (glare) std::printf("glare probe with the smooth sphere: %.3f ms\n", probe_ms(*renderers[0], snap));
    std::printf(
        "\n| budget px | cut tiles | triangles drawn | ms/frame | frame / trivial | terrain extra / trivial |%s\n",
        glare ? " glare probe ms |" : "");
    std::printf("|---|---|---|---|---|---|%s\n", glare ? "---|" : "");
    const uint16_t earth = scenes[1].find("earth")->id;
    for (size_t i = 1; i < budgets.size(); ++i) {
        const TerrainFrameStats& st = renderers[i]->terrain().last_frame(earth);
        const double t = percentile(ms[i + 1], 0.5);
        std::printf("| %.1f | %zu | %zu | %.2f | %.1f | %.1f |", budgets[i], st.cut_tiles, st.triangles, t,
                    t / t_trivial, (t - t_smooth) / t_trivial);
        if (glare) std::printf(" %.3f |", probe_ms(*renderers[i], snap));
        std::printf("\n");
    }

    // Streaming: a descent from 20 km to 200 m, fresh renderers, the fast source then the slow one.
    std::printf("\nstreaming, a %d-frame descent from 20 km to 200 m at 1 px:\n", path);
    for (const bool slow : {false, true}) {
        SceneRenderer r(cluster, ch, scenes[2]);
        if (slow)
            r.terrain().set_build_hook([slow_ms](const terrain::TileKey&) {
                std::this_thread::sleep_for(std::chrono::milliseconds(slow_ms));
            });
        std::vector<double> t;
        int with_stand_ins = 0;
        for (int f = 0; f < path; ++f) {
            const double h = 20e3 * std::pow(200.0 / 20e3, static_cast<double>(f) / (path - 1));
            const Snapshot s = evening_view(scenes[2], h);
            t.push_back(ms_of([&] { r.render(s); }));
            if (r.terrain().last_frame(earth).stand_ins > 0) ++with_stand_ins;
        }
        std::printf("  %s source: frame median %.2f ms, p90 %.2f ms, frames with stand-ins %d of %d\n",
                    slow ? "slow" : "fast", percentile(t, 0.5), percentile(t, 0.9), with_stand_ins, path);
    }
    return 0;
}

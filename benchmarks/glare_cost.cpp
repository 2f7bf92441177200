// Glare cost, glare accuracy and visibility accuracy per channel: one channel looking at the Sun
// half hidden behind the Moon, rendered by the real SceneRenderer (EGL, the slave's passes),
// with the glare off and on. Costs are ms per frame and, for the glare (probe + occlusion
// queries + halo + glare passes: the frame with it minus the frame without), a ratio to a
// trivial full-screen pass (one texel copied per pixel into an RGBA32F target of the channel's
// size) timed in the same run.
//   - the glare split (slave/passes/glare_halo_pass.hpp) at halo_downsample 2, 4 and 8 against
//     the whole PSF per pixel (halo_downsample 1): cost, and the relative luminance error of the
//     added radiance (max and p99 where the glare is displayable, energy, largest difference in
//     display units);
//   - the probe size (halo_downsample 4): the visible fraction the queries measured against the
//     analytic one (common/glare/analytic_visibility, the same eclipse math).
// --image FILE writes the before/after picture of docs/images/glare-halo.png.
//   build/bin/glare_cost [--size 512] [--frames 20] [--image docs/images/glare-halo.png]
#include <CLI/CLI.hpp>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "glare/analytic_visibility.hpp"
#include "glare/glare_sources.hpp"
#include "scene_renderer.hpp"
#include "show_script.hpp"
#include "passes/render_pass.hpp"
#include "util/cli_parse.hpp"

using namespace cupola;

namespace {

glm::dvec3 position_of(const Snapshot& s, uint16_t id) {
    for (const auto& b : s.bodies)
        if (b.id == id) return b.position_m;
    return {};
}

double time_ms(const std::function<void()>& draw, int frames) {
    for (int i = 0; i < 2; ++i) draw();  // warm-up (shader compile, first upload)
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) draw();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / frames;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// A pass that draws nothing: when the renderer prepares it, it waits for what the passes before
// it drew (glFinish) and notes the time. Two of them around the glare passes time those alone.
class FinishStamp : public RenderPass {
public:
    std::string name() const override { return "finish stamp"; }
    PassIo io() const override { return {}; }
    int prepare(const FrameContext&) override {
        glFinish();
        at.push_back(std::chrono::steady_clock::now());
        return 0;
    }
    void draw(const PassInputs&, int) override {}
    std::vector<std::chrono::steady_clock::time_point> at;
};

// Stamps before the first glare pass ("glare halo" or "glare") and after "glare"; none when the
// renderer has no glare.
std::pair<FinishStamp*, FinishStamp*> bracket_glare(SceneRenderer& r) {
    auto names = r.pass_names();
    const auto first =
        std::find_if(names.begin(), names.end(), [](auto& n) { return n == "glare halo" || n == "glare"; });
    if (first == names.end()) return {nullptr, nullptr};
    const size_t begin = static_cast<size_t>(first - names.begin());
    const size_t end = static_cast<size_t>(std::find(names.begin(), names.end(), "glare") - names.begin()) + 1;
    auto after = std::make_unique<FinishStamp>(), before = std::make_unique<FinishStamp>();
    std::pair<FinishStamp*, FinishStamp*> out{before.get(), after.get()};
    r.insert_pass(end, std::move(after));
    r.insert_pass(begin, std::move(before));
    return out;
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// The Sun's centre on the Moon's limb, seen from 40 lunar radii; the scene's atmospheres dropped.
Snapshot moon_limb_view(SceneConfig& scene) {
    for (auto& b : scene.bodies) {
        b.atmosphere.present = false;
        if (b.kind != BodyKind::Star) b.texture = "generated:" + b.name;
    }
    const uint16_t sun = scene.find("sun")->id, moon = scene.find("moon")->id;
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
    return snap;
}

struct Case {
    std::string glare;  // "off", "full", "split"
    int downsample = 1, probe = 64;
    bool rays = true;  // false: streak_contrast 0 (what the rays cost)
};

// The relative luminance error of `split` against `full` (frames minus the frame without glare)
// where the full glare is displayable (at least min_display after the exposure).
void print_error(const Image& split, const Image& full, const Image& off, double exposure, double min_display) {
    std::vector<double> rel;
    double es = 0.0, ef = 0.0, worst_display = 0.0;
    for (int y = 0; y < full.height; ++y)
        for (int x = 0; x < full.width; ++x) {
            const double o = luminance(off.pixel(x, y));
            const double f = luminance(full.pixel(x, y)) - o, s = luminance(split.pixel(x, y)) - o;
            worst_display = std::max(worst_display, std::abs(s - f) * exposure);
            if (!(f * exposure >= min_display)) continue;
            rel.push_back(std::abs(s - f) / f);
            es += s, ef += f;
        }
    std::sort(rel.begin(), rel.end());
    const double p99 = rel.empty() ? 0.0 : rel[static_cast<size_t>(0.99 * (rel.size() - 1))];
    std::printf(" %.2f %% | %.2f %% | %+.3f %% | %.1e |", rel.empty() ? 0.0 : 100.0 * rel.back(), 100.0 * p99,
                100.0 * (es / ef - 1.0), worst_display);
}

// Before (the PSF per pixel), after (the split) and 100 x their difference, 2 x 2 pixels averaged.
void write_image(const std::string& path, const Image& full, const Image& split, const Image& off, float exposure) {
    const int w = full.width / 2, h = full.height / 2;
    std::vector<uint8_t> rgba(static_cast<size_t>(3 * w) * h * 4, 255);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                double f = 0.0, s = 0.0, o = 0.0;
                for (int k = 0; k < 4; ++k) {
                    f += full.pixel(2 * x + k % 2, 2 * y + k / 2)[c];
                    s += split.pixel(2 * x + k % 2, 2 * y + k / 2)[c];
                    o += off.pixel(2 * x + k % 2, 2 * y + k / 2)[c];
                }
                const float diff = static_cast<float>(100.0 * std::abs(s - f) / 4.0 * exposure);
                const float v[3] = {static_cast<float>(f / 4.0 * exposure), static_cast<float>(s / 4.0 * exposure),
                                    diff};
                for (int panel = 0; panel < 3; ++panel)
                    rgba[((static_cast<size_t>(y) * 3 * w) + panel * w + x) * 4 + c] =
                        static_cast<uint8_t>(std::lround(255.0f * linear_to_srgb(v[panel])));
            }
    auto out = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(3 * w, h, 4, OIIO::TypeDesc::UINT8);
    if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) || !out->close())
        throw std::runtime_error("cannot write " + path);
    std::printf("wrote %s\n", path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Glare cost (ms per frame per channel, ratio to a trivial pass), error and visibility accuracy"};
    int size = 512, frames = 20;
    std::string scene_file = "configs/scenes/earth-moon.json", image;
    app.add_option("--size", size, "channel width and height in pixels")->check(CLI::Range(16, 8192));
    app.add_option("--frames", frames, "timed frames per case")->check(CLI::Range(1, 100000));
    app.add_option("--scene", scene_file, "scene (its atmospheres are dropped: space view)")->check(CLI::ExistingFile);
    app.add_option("--image", image, "write the before/after picture (PNG) here");
    if (auto rc = parse_command_line(app, argc, argv, "glare_cost")) return *rc;

    SceneConfig scene = load_scene_config(scene_file);
    const Snapshot snap = moon_limb_view(scene);
    const uint16_t sun = scene.find("sun")->id;
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
    const std::vector<Case> cases = {{"off"},
                                     {"full", 1},
                                     {"split", 2},
                                     {"split", 4},
                                     {"split", 8},
                                     {"full", 1, 64, false},
                                     {"split", 4, 64, false},
                                     {"split", 4, 16},
                                     {"split", 4, 32},
                                     {"split", 4, 128}};
    std::vector<std::unique_ptr<SceneRenderer>> renderers;
    std::vector<SceneConfig> scenes;
    for (const Case& c : cases) {
        SceneConfig s = scene;
        s.glare.enabled = c.glare != "off";
        s.glare.halo_downsample = c.downsample;
        s.glare.probe_size = c.probe;
        if (!c.rays) s.glare.streak_contrast = 0.0;
        scenes.push_back(s);
    }
    std::vector<std::pair<FinishStamp*, FinishStamp*>> stamps;
    for (const SceneConfig& s : scenes) {
        renderers.push_back(std::make_unique<SceneRenderer>(cluster, ch, s));
        stamps.push_back(bracket_glare(*renderers.back()));
    }
    GlFramebuffer trivial_target(size, size);
    const std::vector<glm::vec4> texels(static_cast<size_t>(size) * size, glm::vec4(0.5f));
    GlTexture source(size, size, texels.data(), GL_NEAREST);
    GlProgram trivial("fullscreen.vert", "fullscreen_copy.frag");
    GlEmptyVertexArray triangle;
    auto trivial_pass = [&] {
        trivial_target.bind();
        trivial.use();
        source.bind(0);
        trivial.set("u_source", 0);
        triangle.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    // Every case is timed in interleaved rounds (the median of 7 is kept), so that drifts of the
    // machine hit every case alike.
    std::vector<std::vector<double>> ms(cases.size() + 1);
    for (int round = 0; round < 7; ++round) {
        ms[0].push_back(time_ms(
            [&] {
                trivial_pass();
                glFinish();  // as the glare passes are timed: each on its own, waited for
            },
            frames));
        for (size_t i = 0; i < cases.size(); ++i)
            ms[i + 1].push_back(time_ms([&] { renderers[i]->render(snap); }, frames));
    }
    const double t_trivial = median(ms[0]), base = median(ms[1]);
    // The glare passes' own time, frame by frame: from the stamps around them.
    std::vector<double> glare_ms(cases.size(), 0.0);
    for (size_t i = 1; i < cases.size(); ++i) {
        std::vector<double> d;
        for (size_t f = 0; f < stamps[i].first->at.size(); ++f)
            d.push_back(
                std::chrono::duration<double, std::milli>(stamps[i].second->at[f] - stamps[i].first->at[f]).count());
        glare_ms[i] = median(d);
    }
    std::printf("trivial full-screen pass: %.3f ms; frame without glare: %.2f ms (%.1f trivial passes)\n\n", t_trivial,
                base, base / t_trivial);
    const Image off = renderers[0]->render(snap), full = renderers[1]->render(snap);
    SceneConfig no_rays = scene;
    no_rays.glare.halo_downsample = 1;
    no_rays.glare.streak_contrast = 0.0;
    const Image full_no_rays = SceneRenderer(cluster, ch, no_rays).render(snap);
    std::printf(
        "| glare | halo_downsample | probe | ms/frame | frame - no glare | glare passes ms | glare passes / trivial "
        "pass | rel. error max | p99 | energy | max diff (display) | measured fraction | error |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 1; i < cases.size(); ++i) {
        const Case& c = cases[i];
        const double t = median(ms[i + 1]);
        std::printf("| %s%s | %d | %d | %.2f | %.2f | %.2f | %.2f |", c.glare.c_str(), c.rays ? "" : ", no rays",
                    c.downsample, c.probe, t, t - base, glare_ms[i], glare_ms[i] / t_trivial);
        const Image img = renderers[i]->render(snap);
        if (c.glare == "full")
            std::printf(" - | - | - | - |");
        else
            print_error(img, c.rays ? full : full_no_rays, off, snap.settings.exposure, scene.glare.min_display);
        double total = 0.0, seen = 0.0;
        for (const auto& m : renderers[i]->glare_measurements())
            if (m.body == sun) total += m.total_sr, seen += m.visible_total_sr();
        const double f = total > 0.0 ? seen / total : -1.0;
        std::printf(" %.5f | %+.2f %% |\n", f, 100.0 * (f / analytic.visible_fraction - 1.0));
        if (!image.empty() && c.rays && c.downsample == scene.glare.halo_downsample &&
            c.probe == scene.glare.probe_size)
            write_image(image, full, img, off, snap.settings.exposure);
    }
    return 0;
}

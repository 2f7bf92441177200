// Frame cost: one channel of the earth-moon scene (configs/scenes/earth-moon.json) rendered by
// the slave's SceneRenderer through EGL, in three views, with the renderer's per-pass timing on
// (SceneRenderer::set_pass_timing: a glFinish after every pass):
//   day     from the ground, the Sun 50 degrees from the zenith and the Moon in view, the
//           horizon across the lower part of the channel;
//   sunset  from the ground, the Sun on the horizon in the middle of the channel;
//   orbit   from 400 km, the limb of the Earth across the channel, the Moon above it;
//   night   (asked for by --views) from the ground, the Sun 30 degrees down, looking east; the
//           scene's bodies other than the Sun, the Earth and the Moon 4 AU away across the view
//           (with --scene configs/scenes/solar-system.json: nine planet points);
//   saturn  (asked for by --views, with the solar-system scene) as night, with Saturn and its rings
//           8 Saturn radii ahead, lit from behind the camera;
//   moonlit (asked for by --views) as night, with the Moon nearly full 40 degrees up in the view:
//           the air lit by the Moon too;
//   far-earth (asked for by --views) the Earth 1.2 degrees in radius from 300 000 km: a small disc
//           of air drawn with 4 x 4 rays a pixel, and its point.
// The snapshot is finished the way the master does it (finish_frame_snapshot: automatic
// exposure, glare sources). In the same process and rounds, a trivial full-screen pass (one
// texel fetched per pixel into an RGBA16F target of the channel's size) is timed, and every cost
// is also given as a ratio to it. Prints one JSON line per view (nlohmann-json):
//   {"view", "size", "frames", "model", "renderer", "read_back", "frame_ms", "untimed_frame_ms",
//    "trivial_ms", "ratio", "ratio_untimed", "passes": {name: ms}, "passes_ratio": {name: ratio}, "read_back_ms",
//    "frame_min_ms", "trivial_min_ms", "ratio_of_minima", "frame_cpu_ms", "trivial_cpu_ms",
//    "ratio_cpu", "camera_altitude_m", "sun_zenith_deg", "sun_step_deg", "halo_separate",
//    "surface_separate", "stars_ignore_sky", "sky_last", "overlays", "stereo"} (with --overlays
//    also "overlays_extra_ms", "overlays_ratio"; with --stereo also "mono_frame_ms", "mono_ratio",
//    "stereo_over_mono": the stereo frame, both eyes and their packing, over the mono one)
// frame_ms is the whole frame with the per-pass waits (their sum plus the CPU set-up),
// untimed_frame_ms the same frame drawn the way the slave draws it (one wait at the end), and
// ratio_untimed that frame over the trivial pass: the waits after every pass cost llvmpipe a
// flush of its rasteriser threads each, which the slave does not pay. With
// --read-back every frame is also read back as RGBA32F (what a files sink needs) and that is
// counted in both; by default nothing is read back. Medians over --frames after --warm-up (the
// trivial pass: three samples per frame); the minima are given too, and the medians of the
// process's CPU time (all threads) per frame and per trivial pass: on a software renderer on a
// machine under load, that ratio is the one that does not depend on what else runs.
// With --sun-step-deg the Sun rises by that much every frame (timed and untimed frames alike), as
// in a show where time runs: the sky-view table is then re-rendered whenever the Sun's zenith
// angle crosses a step of the table's grid, and those renders are counted in the frames.
//   build/bin/frame_cost [--size 1024] [--frames 10] [--model NAME] [--read-back] [--views day,orbit]
//                        [--images DIR] [--sun-step-deg D] [--halo-separate] [--surface-separate]
//                        [--stars-ignore-sky] [--sky-last] [--overlays all|NAME,...] [--stereo MODE]
// With --overlays the scene's overlays named (or all) are shown (the pass "overlays"), and every
// round also draws the untimed frame without them, right after it: "overlays_extra_ms" is the
// median of those differences and "overlays_ratio" that over the trivial pass, the overlays' cost.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "atmosphere/auto_exposure.hpp"
#include "atmosphere/production_quality.hpp"
#include "atmosphere/scene_atmospheres.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "glare/glare_sources.hpp"
#include "image/frame_image.hpp"
#include "master_node.hpp"
#include "scene_renderer.hpp"
#include "show_script.hpp"
#include "util/cli_parse.hpp"

using namespace cupola;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kAu_m = 1.495978707e11;
constexpr double kMoonDistance_m = 3.844e8;
constexpr double kFrameInterval_s = 1.0 / 60.0;
constexpr int kTrivialPerFrame = 3;  // the trivial pass is short: more samples of it per frame

// Where the camera is and looks, and where the Sun and the Moon are, in the observer's local
// horizon frame (azimuth from north towards east, elevation above the horizontal).
struct ViewSpec {
    std::string name;
    double altitude_m = 0.0;
    double look_az_deg = 0.0, look_el_deg = 0.0;
    double sun_az_deg = 0.0, sun_el_deg = 0.0;
    double moon_az_deg = 0.0, moon_el_deg = 0.0;
};

const std::vector<ViewSpec>& all_views() {
    // The channel spans 45 degrees each way from its centre (FovDeg{45, 45, 45, 45}).
    static const std::vector<ViewSpec> v = {
        {"day", 2.0, 25.0, 20.0, 0.0, 40.0, 55.0, 15.0},
        {"sunset", 2.0, 0.0, 10.0, 0.0, 0.0, 150.0, 20.0},
        // From 400 km the horizon lies acos(R / (R + h)) = 19.7 degrees below the horizontal.
        {"orbit", 400.0e3, 0.0, -15.0, 90.0, 30.0, -20.0, 10.0},
        // Night: the Sun 30 degrees down; the scene's other bodies (solar-system.json's planets)
        // 4 AU away across the view, each a point (planet_point_pass).
        {"night", 2.0, 100.0, 20.0, 280.0, -30.0, 250.0, -10.0},
        // As night, with the scene's Saturn 8 of its radii ahead (its rings 32 degrees each way).
        {"saturn", 2.0, 100.0, 20.0, 280.0, -30.0, 250.0, -10.0},
        // As night, with the Moon nearly full 40 degrees up in the view: the moonlit sky
        // (common/atmosphere/moonlit_sky.hpp), its own sky-view table and a second look-up per pixel.
        {"moonlit", 2.0, 100.0, 20.0, 280.0, -30.0, 100.0, 40.0},
        // From about the Moon's distance, straight down at the Earth, 1.2 degrees in radius (14
        // pixels at 1024): between point and disc, its air drawn with 4 x 4 rays a pixel
        // (PlanetLight::supersample) and its point beside it.
        {"far-earth", 2.976e8, 0.0, -89.9, 90.0, 30.0, 0.0, -10.0},
    };
    return v;
}

// Unit vector in the local frame: x east, y north, z up (the Earth's centre at the origin and
// the observer on +z, so these are also the world axes of the snapshot).
glm::dvec3 local_direction(double az_deg, double el_deg) {
    const double az = glm::radians(az_deg), el = glm::radians(el_deg);
    return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
}

Snapshot view_snapshot(const ViewSpec& v, const SceneConfig& scene, const ClusterConfig& cluster,
                       const AutoExposure& exposure, const GlareSources* glare) {
    Snapshot s;
    s.bodies.resize(scene.bodies.size());
    for (auto& b : s.bodies) b.id = static_cast<uint16_t>(&b - s.bodies.data());
    const BodyConfig* earth = scene.find("earth");
    if (!earth) throw std::runtime_error("the scene has no body named \"earth\"");
    s.bodies[earth->id].position_m = glm::dvec3(0.0);
    if (const BodyConfig* sun = scene.find("sun"))
        s.bodies[sun->id].position_m = kAu_m * local_direction(v.sun_az_deg, v.sun_el_deg);
    if (const BodyConfig* moon = scene.find("moon"))
        s.bodies[moon->id].position_m = kMoonDistance_m * local_direction(v.moon_az_deg, v.moon_el_deg);
    int others = 0;
    for (const BodyConfig& b : scene.bodies)
        if (b.name != "sun" && b.name != "earth" && b.name != "moon")
            s.bodies[b.id].position_m =
                4.0 * kAu_m * local_direction(v.look_az_deg - 35.0 + 9.0 * others++, v.look_el_deg);
    const glm::dvec3 up(0, 0, 1);
    s.camera_position_m = (earth->radius_m + v.altitude_m) * up;
    // Camera frame columns: +X right, +Y up, +Z back.
    const glm::dvec3 forward = local_direction(v.look_az_deg, v.look_el_deg);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
    s.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(right, forward), -forward));
    if (v.name == "saturn") {
        const BodyConfig* saturn = scene.find("saturn");
        if (!saturn) throw std::runtime_error("the saturn view needs a scene with saturn (solar-system.json)");
        s.bodies[saturn->id].position_m = s.camera_position_m + 8.0 * saturn->radius_m * forward;
    }
    s.sim_time_s = 0.0;
    finish_frame_snapshot(s, ShowSettings{}, cluster, scene, 1, kFrameInterval_s, &exposure, glare);
    return s;
}

// The trivial full-screen pass costs are measured against: one texel of an RGBA16F source
// fetched per pixel (shaders/fullscreen_copy.frag) into an RGBA16F target of the same size.
class TrivialPass {
public:
    explicit TrivialPass(int size) : size_(size), program_("fullscreen.vert", "fullscreen_copy.frag") {
        for (GLuint* t : {&source_, &target_}) {
            glCreateTextures(GL_TEXTURE_2D, 1, t);
            glTextureStorage2D(*t, 1, GL_RGBA16F, size, size);
            glTextureParameteri(*t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(*t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        const std::vector<float> grey(static_cast<size_t>(size) * size * 4, 0.5f);
        glTextureSubImage2D(source_, 0, 0, 0, size, size, GL_RGBA, GL_FLOAT, grey.data());
        glCreateFramebuffers(1, &fbo_);
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, target_, 0);
        if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("the RGBA16F target of the trivial pass is not complete");
        gl::check("frame_cost: trivial pass set-up");
    }
    ~TrivialPass() {
        glDeleteFramebuffers(1, &fbo_);
        glDeleteTextures(1, &source_);
        glDeleteTextures(1, &target_);
    }
    TrivialPass(const TrivialPass&) = delete;
    TrivialPass& operator=(const TrivialPass&) = delete;

    // One pass, waited for; its wall time in ms.
    double run() {
        const auto t0 = Clock::now();
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glViewport(0, 0, size_, size_);
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        program_.use();
        glBindTextureUnit(0, source_);
        program_.set("u_source", 0);
        triangle_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glFinish();
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    }

private:
    int size_;
    GlProgram program_;
    GlEmptyVertexArray triangle_;
    GLuint source_ = 0, target_ = 0, fbo_ = 0;
};

// CPU time of the whole process, every thread (llvmpipe's rasteriser threads too), in ms: on a
// software renderer the work itself, whatever else the machine runs; on a GPU mostly waiting.
double process_cpu_ms() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Options {
    int size = 1024, frames = 10, warm_up = 2, device = -1;
    bool read_back = false, halo_separate = false, surface_separate = false, stars_ignore_sky = false;
    bool sky_last = false;
    std::vector<std::string> overlays;  // shown: names (common/overlay/overlay_kind.hpp) or "all"
    double sun_step_deg = 0.0;
    std::string scene_file = std::string(CUPOLA_SOURCE_DIR) + "/configs/scenes/earth-moon.json";
    std::string model, images;
    std::vector<std::string> views = {"day", "sunset", "orbit"};
    std::string stereo = "mono";  // the channel's stereo mode (projection/stereo_mode.hpp)
};

// The scene with the Earth's atmosphere at the chosen quality; a surface map that is not on
// this machine (e.g. xplanet's Earth on a render node) is replaced by a generated one, said on stderr.
SceneConfig load_scene(const Options& o, std::string& model) {
    SceneConfig scene = load_scene_config(o.scene_file);
    const auto names = atmosphere::production_quality_names();
    if (!o.model.empty() && std::find(names.begin(), names.end(), o.model) == names.end()) {
        std::string choices;
        for (const auto& n : names) choices += (choices.empty() ? "" : ", ") + n;
        throw std::runtime_error("--model \"" + o.model + "\" is not a quality level (" + choices + ")");
    }
    for (auto& b : scene.bodies) {
        if (b.atmosphere.present && !o.model.empty()) b.atmosphere.model = o.model;
        if (b.atmosphere.present && b.name == "earth") model = b.atmosphere.model;
        if (b.texture.rfind("generated:", 0) != 0 && !fs::exists(b.texture)) {
            std::fprintf(stderr, "frame_cost: %s's texture %s is missing; using generated:%s\n", b.name.c_str(),
                         b.texture.c_str(), b.name.c_str());
            b.texture = "generated:" + b.name;
        }
    }
    return scene;
}

ClusterConfig one_channel(int size, const std::string& stereo = "mono") {
    ClusterConfig cluster;
    ChannelConfig ch;
    ch.id = 0;
    ch.name = "frame-cost";
    ch.fov = FovDeg{45, 45, 45, 45};
    ch.width = ch.height = size;
    ch.stereo = stereo_mode_from_name(stereo);
    cluster.channels = {ch};
    cluster.output.auto_exposure.enabled = true;
    return cluster;
}

// Per frame of one view: the trivial pass, a timed frame and an untimed one, interleaved so
// that drifts of the machine hit all three alike.
struct ViewTimes {
    std::vector<double> trivial, frame, untimed, read_back;
    std::vector<double> overlays_extra;  // with --overlays: each round's untimed frame minus the same without them
    std::vector<double> mono;            // with --stereo: each round's mono frame of the same snapshot
    std::vector<double> trivial_cpu, frame_cpu;  // the process's CPU time (all its threads)
    std::map<std::string, std::vector<double>> passes;
    std::vector<std::string> order;  // pass names in run order
};

double one_frame(SceneRenderer& r, const Snapshot& snap, bool read_back) {
    const auto t0 = Clock::now();
    if (read_back)
        r.render(snap);
    else
        r.draw(snap);
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The snapshot of frame i (warm-up frames first): the view's, with the Sun raised by i times
// --sun-step-deg (0: the same snapshot every frame).
using FrameSnapshots = std::function<Snapshot(int)>;

// The untimed frame of a snapshot with every overlay hidden (the overlays' cost is the difference
// of two frames drawn one after the other, which a drift of the machine hits alike).
double untimed_without_overlays(SceneRenderer& r, Snapshot snap, const Options& o) {
    snap.settings.overlay_alpha.fill(0.0f);
    return one_frame(r, snap, o.read_back);
}

ViewTimes time_view(SceneRenderer& r, TrivialPass& trivial, const FrameSnapshots& snaps, const Options& o,
                    SceneRenderer* mono) {
    for (int i = 0; i < o.warm_up; ++i) {
        trivial.run();
        one_frame(r, snaps(i), o.read_back);
    }
    ViewTimes t;
    for (int i = 0; i < o.frames; ++i) {
        const Snapshot snap = snaps(o.warm_up + 2 * i);
        const Snapshot next = snaps(o.warm_up + 2 * i + 1);
        for (int k = 0; k < kTrivialPerFrame; ++k) {
            const double cpu0 = process_cpu_ms();
            t.trivial.push_back(trivial.run());
            t.trivial_cpu.push_back(process_cpu_ms() - cpu0);
        }
        r.set_pass_timing(true);
        const double cpu0 = process_cpu_ms();
        one_frame(r, snap, o.read_back);
        t.frame_cpu.push_back(process_cpu_ms() - cpu0);
        r.set_pass_timing(false);
        const FrameTimings& ft = r.last_frame_timings();
        t.frame.push_back(ft.frame_ms);
        t.read_back.push_back(ft.read_back_ms);
        for (const auto& [name, ms] : ft.passes_ms) {
            if (!t.passes.count(name)) t.order.push_back(name);
            t.passes[name].push_back(ms);
        }
        t.untimed.push_back(one_frame(r, next, o.read_back));
        if (!o.overlays.empty()) t.overlays_extra.push_back(t.untimed.back() - untimed_without_overlays(r, next, o));
        if (mono) t.mono.push_back(one_frame(*mono, next, o.read_back));
    }
    return t;
}

// With --stereo: the mono frame of each round's snapshot, and the stereo frame over it (per round,
// then the median): what the second eye and the packing cost.
void add_stereo_figures(nlohmann::ordered_json& j, const ViewTimes& t, double trivial_ms) {
    std::vector<double> over;
    for (size_t i = 0; i < t.mono.size(); ++i) over.push_back(t.mono[i] > 0.0 ? t.untimed[i] / t.mono[i] : 0.0);
    j["mono_frame_ms"] = median(t.mono);
    j["mono_ratio"] = trivial_ms > 0.0 ? median(t.mono) / trivial_ms : 0.0;
    j["stereo_over_mono"] = median(over);
}

nlohmann::ordered_json view_line(const ViewSpec& v, const ViewTimes& t, const Options& o, const std::string& model,
                                 const std::string& renderer) {
    const double trivial_ms = median(t.trivial), frame_ms = median(t.frame);
    nlohmann::ordered_json j;
    j["view"] = v.name;
    j["size"] = o.size;
    j["frames"] = o.frames;
    j["model"] = model;
    j["renderer"] = renderer;
    j["read_back"] = o.read_back;
    j["frame_ms"] = frame_ms;
    j["untimed_frame_ms"] = median(t.untimed);
    j["trivial_ms"] = trivial_ms;
    j["ratio"] = trivial_ms > 0.0 ? frame_ms / trivial_ms : 0.0;
    j["ratio_untimed"] = trivial_ms > 0.0 ? median(t.untimed) / trivial_ms : 0.0;
    if (!t.overlays_extra.empty()) {
        j["overlays_extra_ms"] = median(t.overlays_extra);
        j["overlays_ratio"] = trivial_ms > 0.0 ? median(t.overlays_extra) / trivial_ms : 0.0;
    }
    if (!t.mono.empty()) add_stereo_figures(j, t, trivial_ms);
    // The fastest of the samples: on a machine shared with other work the least disturbed ones.
    const double trivial_min = *std::min_element(t.trivial.begin(), t.trivial.end());
    const double frame_min = *std::min_element(t.frame.begin(), t.frame.end());
    j["frame_min_ms"] = frame_min;
    j["trivial_min_ms"] = trivial_min;
    j["ratio_of_minima"] = trivial_min > 0.0 ? frame_min / trivial_min : 0.0;
    const double trivial_cpu = median(t.trivial_cpu), frame_cpu = median(t.frame_cpu);
    j["frame_cpu_ms"] = frame_cpu;
    j["trivial_cpu_ms"] = trivial_cpu;
    j["ratio_cpu"] = trivial_cpu > 0.0 ? frame_cpu / trivial_cpu : 0.0;
    nlohmann::ordered_json passes = nlohmann::ordered_json::object(), ratios = nlohmann::ordered_json::object();
    for (const auto& name : t.order) {
        const double ms = median(t.passes.at(name));
        passes[name] = ms;
        ratios[name] = trivial_ms > 0.0 ? ms / trivial_ms : 0.0;
    }
    j["passes"] = passes;
    j["passes_ratio"] = ratios;
    j["read_back_ms"] = median(t.read_back);
    j["camera_altitude_m"] = v.altitude_m;
    j["sun_zenith_deg"] = 90.0 - v.sun_el_deg;
    j["sun_step_deg"] = o.sun_step_deg;
    j["halo_separate"] = o.halo_separate;
    j["surface_separate"] = o.surface_separate;
    j["stars_ignore_sky"] = o.stars_ignore_sky;
    j["sky_last"] = o.sky_last;
    j["overlays"] = o.overlays;
    j["stereo"] = o.stereo;
    return j;
}

// DIR/frame-cost-<view>.png: the frame as a files sink would write it, to look at the views.
void write_view_image(const std::string& dir, const ViewSpec& v, SceneRenderer& r, const Snapshot& snap) {
    const Image image = r.render(snap);
    FrameMetadata meta;
    meta.channel_name = v.name;
    const auto paths = write_frame(dir, image, meta, {"png"}, snap.settings.exposure);
    const fs::path named = fs::path(dir) / ("frame-cost-" + v.name + ".png");
    fs::rename(paths.at(0), named);
    std::fprintf(stderr, "frame_cost: wrote %s (exposure %.3g)\n", named.c_str(), snap.settings.exposure);
}

const ViewSpec& find_view(const std::string& name) {
    for (const auto& v : all_views())
        if (v.name == name) return v;
    throw std::runtime_error("no view named \"" + name + "\" (day, sunset, orbit, night, saturn)");
}

void configure(SceneRenderer& r, const Options& o) {
    r.set_halo_with_atmosphere(!o.halo_separate);
    r.set_surface_with_atmosphere(!o.surface_separate);
    r.set_stars_see_the_sky(!o.stars_ignore_sky);
    r.set_sky_first(!o.sky_last);
}

int run(const Options& o) {
    spdlog::set_level(spdlog::level::warn);
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    std::vector<const ViewSpec*> views;
    for (const auto& name : o.views) views.push_back(&find_view(name));
    std::string model = "none";
    const SceneConfig scene = load_scene(o, model);
    const ClusterConfig cluster = one_channel(o.size, o.stereo);
    EglContext gl(o.device);
    const std::string renderer = gl.info().renderer;
    std::fprintf(stderr, "frame_cost: renderer %s (%s), %d^2, %d frames after %d warm-up\n", renderer.c_str(),
                 gl.info().platform.c_str(), o.size, o.frames, o.warm_up);
    const SceneAtmospheres atmospheres(scene);
    const AutoExposure exposure(cluster, scene, &atmospheres);
    std::unique_ptr<GlareSources> glare;
    if (scene.glare.enabled) glare = std::make_unique<GlareSources>(scene, &atmospheres);
    SceneRenderer r(cluster, cluster.channels[0], scene);
    configure(r, o);
    // With --stereo, the same channel in mono, drawn after each round's stereo frame.
    const ClusterConfig mono_cluster = one_channel(o.size);
    std::unique_ptr<SceneRenderer> mono;
    if (o.stereo != "mono") mono = std::make_unique<SceneRenderer>(mono_cluster, mono_cluster.channels[0], scene);
    if (mono) configure(*mono, o);
    TrivialPass trivial(o.size);
    for (const ViewSpec* v : views) {
        // With --overlays every overlay is fully in (the scene's overlays: the earth-moon scene's).
        const auto with_overlays = [&](Snapshot s) {
            for (const std::string& name : o.overlays) {
                if (name == "all")
                    s.settings.overlay_alpha.fill(1.0f);
                else
                    s.settings.overlay_alpha[static_cast<size_t>(overlay_from_name(name))] = 1.0f;
            }
            return s;
        };
        const Snapshot snap = with_overlays(view_snapshot(*v, scene, cluster, exposure, glare.get()));
        if (!o.images.empty()) write_view_image(o.images, *v, r, snap);
        const FrameSnapshots snaps = [&](int i) {
            if (o.sun_step_deg == 0.0) return snap;
            ViewSpec moved = *v;
            moved.sun_el_deg += i * o.sun_step_deg;
            return with_overlays(view_snapshot(moved, scene, cluster, exposure, glare.get()));
        };
        const ViewTimes t = time_view(r, trivial, snaps, o, mono.get());
        std::printf("%s\n", view_line(*v, t, o, model, renderer).dump().c_str());
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Frame cost of one earth-moon channel in three views, per pass and against a trivial pass"};
    Options o;
    app.add_option("--size", o.size, "channel width and height in pixels")->check(CLI::Range(16, 8192));
    app.add_option("--stereo", o.stereo,
                   "the channel's stereo (mono, side_by_side, top_bottom_half, anaglyph, ...): each round also draws "
                   "the mono frame (mono_frame_ms, stereo_over_mono)");
    app.add_option("--frames", o.frames, "timed frames per view (medians reported)")->check(CLI::Range(1, 100000));
    app.add_option("--warm-up", o.warm_up, "untimed frames per view first")->check(CLI::Range(0, 1000));
    app.add_flag("--surface-separate", o.surface_separate,
                 "the body pass draws the Earth's surface, never the atmosphere (for comparison)");
    app.add_flag("--halo-separate", o.halo_separate,
                 "the glare pass draws the glare's halo on its own, never the atmosphere (for comparison)");
    app.add_flag("--stars-ignore-sky", o.stars_ignore_sky,
                 "every star the exposure can show is drawn, the sky behind it not considered (for comparison)");
    app.add_flag("--sky-last", o.sky_last,
                 "the stars, the Sun and the bodies are drawn before the sky, never after it (for comparison)");
    app.add_option("--overlays", o.overlays,
                   "overlays shown (the pass 'overlays'): all, or names such as constellations,constellation_names,"
                   "boundaries,grid_altaz,grid_equatorial,grid_ecliptic,horizon,meridian,cardinals,labels")
        ->delimiter(',');
    app.add_option("--sun-step-deg", o.sun_step_deg,
                   "raise the Sun by this much every frame (0: a static view; the sky-view table is re-rendered "
                   "when the Sun's zenith angle crosses a step of its grid)");
    app.add_option("--model", o.model, "atmosphere quality level (default: the scene's)");
    app.add_option("--scene", o.scene_file, "scene file (bodies named sun, earth and moon)")->check(CLI::ExistingFile);
    app.add_flag("--read-back", o.read_back, "also read every frame back as RGBA32F (what a files sink needs)");
    app.add_option("--views", o.views, "views to run: day, sunset, orbit, night, saturn, moonlit, far-earth")
        ->delimiter(',');
    app.add_option("--device", o.device, "EGL device index (-1: the first that works, else surfaceless)");
    app.add_option("--images", o.images, "also write DIR/frame-cost-<view>.png")->check(CLI::ExistingDirectory);
    if (auto rc = parse_command_line(app, argc, argv, "frame_cost")) return *rc;
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "frame_cost: %s\n", e.what());
        return 1;
    }
}

// The deferred atmosphere pass on a real headless EGL context (llvmpipe on CI): the GPU agrees
// with the CPU running the same shared code, channels tile without seams, only bodies with an
// atmosphere cost anything, and the hard geometric cases stay finite. Small images only.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>

#include "atmosphere/production_model.hpp"
#include "passes/atmosphere_pass.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "image/frame_image.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;
namespace at = cupola::atmosphere;
namespace sh = cupola::shading;

namespace {

constexpr double kAu = 1.495978707e11;
constexpr double kEarthRadius = 6.371e6;
constexpr double kSunRadius = 6.957e8, kSunRadiance = 5.8e4, kSunLimbU = 0.6;
constexpr double kAlbedo = 0.3;
constexpr uint16_t kSun = 0, kEarth = 1, kRock = 2;

// One context for the whole executable, created with no window system in the environment; the
// atmosphere tables go to a scratch cache (built by the first renderer, loaded by the others).
EglContext& context() { return test::headless_gl("AtmosphereRender"); }

// A scene file: the Sun, an Earth-sized planet (white texture, albedo kAlbedo) with the given
// atmosphere model ("" for none), and optionally a 1 m rock.
SceneConfig make_scene(const std::string& tag, const std::string& model, bool rock = false) {
    const std::string dir = test::scratch_dir("AtmosphereRender_" + tag);
    std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
    for (int i = 0; i < 8; ++i) hdr += std::string("\x80\x80\x80\x81", 4);  // RGBE 1.0
    test::write_text(dir + "/white.hdr", hdr);
    test::write_text(dir + "/stars.csv", "ra_deg,dec_deg,vmag,bv,name\n10.0,10.0,5.0,0.6,Faint\n");
    const std::string atm =
        model.empty() ? "" : R"(, "atmosphere": { "preset": "earth", "model": ")" + model + R"(" })";
    std::string json = R"({ "bodies": [
        { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 5.8e4,
          "limb_darkening_u": 0.6 },
        { "name": "earth", "kind": "planet", "ephemeris": "earth", "radius_m": 6.371e6, "texture": "white.hdr",
          "albedo": 0.3)" +
                       atm + " }";
    if (rock)
        json += R"(,
        { "name": "rock", "kind": "moon", "ephemeris": "moon", "radius_m": 1.0, "texture": "white.hdr", "albedo": 0.5 })";
    json += R"( ],
      "stars": { "catalog": "stars.csv", "magnitude_limit": -2.0 } })";
    test::write_text(dir + "/scene.json", json);
    return load_scene_config(dir + "/scene.json");
}

ChannelConfig channel(int w, int h, FovDeg f, EulerDeg e = {}) {
    ChannelConfig c;
    c.name = "test";
    c.width = w;
    c.height = h;
    c.fov = f;
    c.orientation = e;
    return c;
}

// The Earth at the origin with its north (world +Z) up at the camera; the camera `altitude_m`
// above the ground on the +Z axis, looking horizontally along world +X (tilted by pitch_deg,
// positive up); the Sun at sun_zenith_deg and sun_azimuth_deg (0 = the view direction, 90 =
// to the left, +Y), 1 AU away.
Snapshot ground_snapshot(double altitude_m, double pitch_deg, double sun_zenith_deg, double sun_azimuth_deg,
                         size_t bodies = 2) {
    Snapshot s;
    s.settings.exposure = 4.0f;
    s.bodies.resize(bodies);
    for (auto& b : s.bodies) b.id = static_cast<uint16_t>(&b - s.bodies.data());
    const double z = glm::radians(sun_zenith_deg), az = glm::radians(sun_azimuth_deg);
    s.bodies[kSun].position_m = kAu * glm::dvec3(std::sin(z) * std::cos(az), std::sin(z) * std::sin(az), std::cos(z));
    s.bodies[kEarth].position_m = glm::dvec3(0.0);
    s.camera_position_m = glm::dvec3(0.0, 0.0, kEarthRadius + altitude_m);
    const double p = glm::radians(pitch_deg);
    const glm::dvec3 fwd(std::cos(p), 0.0, std::sin(p)), up(-std::sin(p), 0.0, std::cos(p));
    s.camera_orientation = glm::quat_cast(glm::dmat3(glm::cross(fwd, up), up, -fwd));
    return s;
}

// The Sun's irradiance at the planet in scene units over the physical spectrum's illuminance.
double solar_scale(const at::ProductionAtmosphere& m, double sun_distance_m) {
    const double ratio = kSunRadius / sun_distance_m;
    const double e_scene = std::numbers::pi * kSunRadiance * ratio * ratio * (1.0 - kSunLimbU / 3.0);
    double e_phys = 0.0;
    for (const auto& w : m.color_weights().texels) e_phys += w.y;
    return e_scene / e_phys;
}

// The CPU evaluation of one pixel of a scene with the planet alone (no stars, the Sun out of
// view): the shared code, composed as atmosphere.frag composes it.
struct CpuComposer {
    const at::ProductionAtmosphere& m;
    sh::vec3 c_hat, sun;
    float d;
    double scale;
    sh::vec4 distances;  // (d, R, d - R, d + R), as the renderer computes them in double
    float sin_alpha;

    glm::dvec3 rgb(const sh::vec3& f) const {
        const sh::sampler2D w{&m.color_weights()};
        return glm::max(
                   glm::dvec3(sh::xyz_to_linear_srgb(sh::atm_samples_to_xyz(f, w, float(m.color_weights().width)))),
                   glm::dvec3(0.0)) *
               scale;
    }

    // The sky-view level, as atmosphere_lookup.frag composes it from the table (built here on the
    // CPU for the same camera distance and Sun zenith cosine).
    glm::dvec3 pixel_from_table(const sh::vec3& v) const {
        using namespace sh;
        const AtmosphereParams& a = m.shader_params();
        const AtmosphereRayStart st = atm_ray_start(a, d, v, c_hat, sun);
        if (!st.valid) return glm::dvec3(0.0);
        const at::SkyViewTable& t = m.sky_view_table(d, -dot(sun, c_hat));
        const bool surface = sphere_hit(v, c_hat, sin_alpha).w >= 0.0f;
        const bool ground = surface || atm_ray_hits_ground(a, st.r_m, st.mu);
        const vec2 uv = atm_sky_view_pixel_uv(a, d, v, c_hat, sun, st, ground, t.size());
        vec3 out = atm_sky_view_inscatter(a, sampler2D{&t.parts[0]}, sampler2D{&t.parts[1]}, uv, st.nu);
        if (ground) out = out + vec3(float(kAlbedo)) * vec3(textureLod(sampler2D{&t.parts[2]}, uv, 0.0));
        return glm::max(glm::dvec3(out), glm::dvec3(0.0)) * scale;
    }

    glm::dvec3 pixel(const sh::vec3& v) const {
        using namespace sh;
        if (m.quality().sky_view) return pixel_from_table(v);
        const AtmosphereParams& a = m.shader_params();
        const auto& t = m.tables();
        const sampler2D trans{&t.transmittance}, ms{&t.multiple_scattering}, irr{&t.irradiance};
        const vec2 ts(t.transmittance.width, t.transmittance.height);
        const vec2 mss(t.multiple_scattering.width, t.multiple_scattering.height);
        const vec2 es(t.irradiance.width, t.irradiance.height);
        const AtmosphereRayStart st = atm_ray_start(a, d, v, c_hat, sun);
        if (!st.valid) return glm::dvec3(0.0);
        const bool ground = atm_ray_hits_ground(a, st.r_m, st.mu);
        const vec4 hit = sphere_hit(v, c_hat, sin_alpha);
        glm::dvec3 base(0.0);
        float t_geometry = -1.0f;
        if (hit.w >= 0.0f) {  // the planet's surface (nothing else in these scenes)
            const float den = std::max(distances.x * dot(v, c_hat) + distances.y * hit.w, 1e-30f);
            const float t_hit = distances.z <= 0.0f ? 0.0f : std::min(distances.z * (distances.w / den), 1e30f);
            const float mu_s_g = clamp(dot(vec3(hit), sun), -1.0f, 1.0f);
            const vec3 e = m.quality().analytic
                               ? atm_analytic_sun(m.analytic_fit(), mu_s_g) * std::max(mu_s_g, 0.0f)
                               : atm_surface_illuminance(a, trans, ts, irr, es, a.bottom_radius_m, mu_s_g);
            base = kAlbedo * rgb(e) / std::numbers::pi;
            t_geometry = ground ? -1.0f : t_hit;
        }
        AtmosphereSegment seg;
        if (m.quality().analytic) {
            float t_end = ground ? atm_distance_to_ground(a, st.r_m, st.mu) : atm_distance_to_top(a, st.r_m, st.mu);
            if (t_geometry >= 0.0f) t_end = std::min(t_end, std::max(t_geometry - st.offset_m, 0.0f));
            seg = atm_analytic(a, m.analytic_fit(), st.r_m, st.mu, st.mu_s, st.nu, t_end);
        } else {
            seg = atm_view_ray(a, trans, ts, ms, mss, m.quality().multiple_scattering, st, t_geometry,
                               m.quality().view_samples);
        }
        return base * glm::dvec3(seg.transmittance) + rgb(seg.inscatter_per_sr);
    }
};

CpuComposer composer(const at::ProductionAtmosphere& m, const Snapshot& s, const glm::dmat3& world_to_channel) {
    const glm::dvec3 rel = s.bodies[kEarth].position_m - s.camera_position_m;
    const double d = glm::length(rel);
    const glm::dvec3 to_sun = s.bodies[kSun].position_m - s.bodies[kEarth].position_m;
    return CpuComposer{m,
                       sh::vec3(world_to_channel * (rel / d)),
                       sh::vec3(world_to_channel * glm::normalize(to_sun)),
                       static_cast<float>(d),
                       solar_scale(m, glm::length(to_sun)),
                       sh::vec4(float(d), float(kEarthRadius), float(d - kEarthRadius), float(d + kEarthRadius)),
                       static_cast<float>(std::min(kEarthRadius / d, 1.0))};
}

// Unit view direction through the centre of image pixel (x, y), row 0 at the top, as
// channel_ray() sees it on the GPU.
sh::vec3 pixel_ray(const ChannelConfig& ch, int x, int y) {
    const ChannelFrustum f = ch.frustum();
    const sh::vec4 tangents(f.tan_left(), f.tan_right(), f.tan_down(), f.tan_up());
    return sh::channel_ray(sh::vec2(x + 0.5f, ch.height - 1 - y + 0.5f), sh::vec2(ch.width, ch.height), tangents);
}

double max_component(const Image& img) {
    double m = 0.0;
    for (size_t i = 0; i < img.rgba.size(); ++i)
        if (i % 4 != 3) m = std::max(m, double(img.rgba[i]));
    return m;
}

// Every colour component finite and not negative; returns how many are not.
int bad_pixels(const Image& img) {
    int bad = 0;
    for (size_t i = 0; i < img.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) bad += !std::isfinite(img.rgba[i + c]) || img.rgba[i + c] < 0.0f;
    return bad;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// From `s` (default: 1.5 m above the ground, looking at the horizon; the Sun 80 degrees from the
// zenith, behind and to the left, out of view).
void expect_gpu_matches_cpu(const std::string& model, const Snapshot& s = ground_snapshot(1.5, 0.0, 80.0, 130.0),
                            bool sky_above = true) {
    context();
    const SceneConfig scene = make_scene("cpu_" + model, model);
    const ChannelConfig ch = channel(64, 48, FovDeg{30, 30, 20, 25});
    ClusterConfig cluster;
    const auto t0 = std::chrono::steady_clock::now();
    SceneRenderer r(cluster, ch, scene);
    const double setup_s = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    const Image img = r.render(s);
    ::testing::Test::RecordProperty("setup_s", std::to_string(setup_s));
    ::testing::Test::RecordProperty("render_s", std::to_string(seconds_since(t1)));
    EXPECT_EQ(r.atmosphere_stats().passes_run, 1);

    const at::ProductionAtmosphere m(scene.bodies[kEarth].atmosphere.parameters, at::production_quality(model));
    const CpuComposer cpu = composer(m, s, glm::transpose(glm::mat3_cast(s.camera_orientation)));
    const double floor = 1e-3 * max_component(img);
    ASSERT_GT(floor, 0.0);
    int worst_x = -1, worst_y = -1;
    double worst = 0.0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::dvec3 want = cpu.pixel(pixel_ray(ch, x, y));
            const float* got = img.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                const double err = std::abs(got[c] - want[c]) / std::max(std::abs(want[c]), floor);
                if (err > worst) worst = err, worst_x = x, worst_y = y;
            }
        }
    ::testing::Test::RecordProperty("worst_relative_error", std::to_string(worst));
    EXPECT_LE(worst, 0.01) << model << ": pixel " << worst_x << "," << worst_y << " GPU "
                           << img.pixel(worst_x, worst_y)[0] << " " << img.pixel(worst_x, worst_y)[1] << " "
                           << img.pixel(worst_x, worst_y)[2] << " CPU " << cpu.pixel(pixel_ray(ch, worst_x, worst_y)).r
                           << " " << cpu.pixel(pixel_ray(ch, worst_x, worst_y)).g << " "
                           << cpu.pixel(pixel_ray(ch, worst_x, worst_y)).b;
    // A sensible picture: a blue sky above (the tables; the analytic fit reddens a low Sun's
    // sky), a lit ground below.
    const float* zenithward = img.pixel(32, 2);
    const float* ground_px = img.pixel(32, 45);
    if (!m.quality().analytic && sky_above) {
        EXPECT_GT(zenithward[2], zenithward[0]) << "the sky should be blue";
    }
    if (sky_above) {
        EXPECT_GT(zenithward[1], 0.0f);
    }
    EXPECT_GT(ground_px[1], 0.0f);
    EXPECT_EQ(bad_pixels(img), 0);
}

}  // namespace

TEST(AtmosphereRender, GpuMatchesCpuFromTheGround) { expect_gpu_matches_cpu("low"); }

TEST(AtmosphereRender, GpuMatchesCpuFromTheGroundAnalytic) { expect_gpu_matches_cpu("analytic"); }

TEST(AtmosphereRender, GpuMatchesCpuFromTheGroundSkyView) { expect_gpu_matches_cpu("sky-view"); }

// From 400 km, looking 20 degrees down at the limb: the sky-view table's outside half against
// the per-pixel march (the GPU-side reference), both rendered by the slave's renderer.
TEST(AtmosphereRender, SkyViewMatchesTheMarchFromOrbit) {
    context();
    const ChannelConfig ch = channel(64, 48, FovDeg{30, 30, 20, 25});
    ClusterConfig cluster;
    const Snapshot s = ground_snapshot(400e3, -20.0, 60.0, 160.0);
    SceneRenderer lookup(cluster, ch, make_scene("orbit_lookup", "sky-view"));
    SceneRenderer march(cluster, ch, make_scene("orbit_march", "medium"));
    const Image a = lookup.render(s), b = march.render(s);
    const double floor = 1e-3 * max_component(b);
    ASSERT_GT(floor, 0.0);
    std::vector<double> err;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c)
                err.push_back(std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]) /
                              std::max(double(b.pixel(x, y)[c]), floor));
    std::sort(err.begin(), err.end());
    const double median = err[err.size() / 2], p99 = err[err.size() * 99 / 100];
    ::testing::Test::RecordProperty("median_relative_difference", std::to_string(median));
    ::testing::Test::RecordProperty("p99_relative_difference", std::to_string(p99));
    EXPECT_LE(median, 0.02);
    EXPECT_LE(p99, 0.10);
    EXPECT_EQ(bad_pixels(a), 0);
}

void expect_no_seam(const std::string& model);

TEST(AtmosphereRender, NoSeamBetweenChannels) { expect_no_seam("low"); }

// The sky-view table depends on nothing of the channel: narrow channels equal the wide one.
TEST(AtmosphereRender, NoSeamBetweenChannelsSkyView) { expect_no_seam("sky-view"); }

void expect_no_seam(const std::string& model) {
    context();
    const SceneConfig scene = make_scene("seam_" + model, model);
    ClusterConfig cluster;
    const int w = 32, h = 32;
    // Tangents [-1, 1] across 2W, and [-1, 0] and [0, 1] across W each: the narrow channels'
    // pixel centres are the wide channel's columns.
    const ChannelConfig wide = channel(2 * w, h, FovDeg{45, 45, 20, 20});
    const ChannelConfig left = channel(w, h, FovDeg{45, 0, 20, 20});
    const ChannelConfig right = channel(w, h, FovDeg{0, 45, 20, 20});
    // A little above the ground, looking slightly down at the horizon, the Sun low and in view
    // on the right (the bright sky around it tests the composition too).
    const Snapshot s = ground_snapshot(200.0, -2.0, 84.0, -20.0);
    SceneRenderer rw(cluster, wide, scene), rl(cluster, left, scene), rr(cluster, right, scene);
    const Image iw = rw.render(s), il = rl.render(s), ir = rr.render(s);
    const double floor = 1e-4 * max_component(iw);
    double worst = 0.0, worst_seam = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < 2 * w; ++x) {
            const float* narrow = x < w ? il.pixel(x, y) : ir.pixel(x - w, y);
            for (int c = 0; c < 3; ++c) {
                const double ref = iw.pixel(x, y)[c];
                const double err = std::abs(narrow[c] - ref) / std::max(std::abs(ref), floor);
                worst = std::max(worst, err);
                if (x == w - 1 || x == w) worst_seam = std::max(worst_seam, err);
            }
        }
    ::testing::Test::RecordProperty("worst_seam_relative_error", std::to_string(worst_seam));
    ::testing::Test::RecordProperty("worst_relative_error", std::to_string(worst));
    EXPECT_LE(worst_seam, 0.01);
    EXPECT_LE(worst, 0.01);
    EXPECT_EQ(bad_pixels(iw), 0);

    // Frames written as the slave writes them carry the snapshot's exposure, identical in both
    // channels (no per-channel exposure), and read back as the same radiance at the seam.
    const std::string dir = test::scratch_dir("AtmosphereRender_seam_frames_" + model);
    FrameMetadata meta;
    meta.channel_id = 0;
    const std::string pl = write_frame(dir + "/left", il, meta, {"exr"}, s.settings.exposure).at(0);
    meta.channel_id = 1;
    const std::string pr = write_frame(dir + "/right", ir, meta, {"exr"}, s.settings.exposure).at(0);
    float exposure[2] = {0.0f, 0.0f};
    int i = 0;
    for (const std::string& p : {pl, pr}) {
        auto in = OIIO::ImageInput::open(p);
        ASSERT_TRUE(in) << p;
        exposure[i++] = in->spec().get_float_attribute("cupola:exposure", -1.0f);
    }
    EXPECT_EQ(exposure[0], s.settings.exposure);
    EXPECT_EQ(exposure[1], exposure[0]);
    const Image fl = read_image_radiance(pl), fr = read_image_radiance(pr);
    for (int y = 0; y < h; ++y)
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(fl.pixel(w - 1, y)[c], iw.pixel(w - 1, y)[c], 0.01 * iw.pixel(w - 1, y)[c] + floor);
            EXPECT_NEAR(fr.pixel(0, y)[c], iw.pixel(w, y)[c], 0.01 * iw.pixel(w, y)[c] + floor);
        }
}

TEST(AtmosphereRender, OnlyWhatTheSceneNeedsIsModelled) {
    context();
    ClusterConfig cluster;
    const ChannelConfig ch = channel(32, 24, FovDeg{30, 30, 20, 20});
    {  // no atmosphere anywhere: no tables, no passes
        const SceneConfig scene = make_scene("none", "");
        SceneRenderer r(cluster, ch, scene);
        r.render(ground_snapshot(1.5, 0.0, 60.0, 0.0));
        const AtmosphereStats st = r.atmosphere_stats();
        EXPECT_EQ(st.tables_built_or_loaded, 0);
        EXPECT_EQ(st.passes_run, 0);
        EXPECT_EQ(st.passes_skipped, 0);
    }
    const SceneConfig scene = make_scene("culling", "low");
    SceneRenderer r(cluster, ch, scene);
    EXPECT_EQ(r.atmosphere_stats().tables_built_or_loaded, 1);
    // 30 000 km above the ground, looking straight away from the planet: skipped.
    Snapshot away = ground_snapshot(3.0e7, 90.0, 60.0, 0.0);
    const Image dark = r.render(away);
    EXPECT_EQ(r.atmosphere_stats().passes_run, 0);
    EXPECT_EQ(r.atmosphere_stats().passes_skipped, 1);
    EXPECT_EQ(bad_pixels(dark), 0);
    // Looking horizontally: the planet (top of the atmosphere 10 degrees in radius) is straight
    // down, 60 degrees below the frustum's lower edge: skipped. Then looking down at it: run.
    Snapshot side = ground_snapshot(3.0e7, 0.0, 60.0, 0.0);
    r.render(side);
    EXPECT_EQ(r.atmosphere_stats().passes_skipped, 2);
    Snapshot down = ground_snapshot(3.0e7, -90.0, 60.0, 0.0);
    const Image lit = r.render(down);
    EXPECT_EQ(r.atmosphere_stats().passes_run, 1);
    EXPECT_EQ(r.atmosphere_stats().passes_skipped, 2);
    EXPECT_GT(max_component(lit), 0.0);
}

// The sky-view table is rendered when the camera's distance or the Sun's angle on the table's grid
// changes, not every frame; the look-up level marches no pass unless an eclipse shadow falls on the planet.
TEST(AtmosphereRender, SkyViewTableIsRenderedOnlyWhenItsInputsChange) {
    context();
    ClusterConfig cluster;
    SceneRenderer r(cluster, channel(32, 24, FovDeg{30, 30, 20, 20}), make_scene("table_reuse", "sky-view"));
    const Snapshot s = ground_snapshot(1.5, 0.0, 60.0, 0.0);
    r.render(s);
    r.render(s);
    EXPECT_EQ(r.atmosphere_stats().passes_run, 2);
    EXPECT_EQ(r.atmosphere_stats().sky_view_renders, 1);
    r.render(ground_snapshot(1.5, 0.0, 61.0, 0.0));  // the Sun moved
    EXPECT_EQ(r.atmosphere_stats().sky_view_renders, 2);
    r.render(ground_snapshot(1.5, 20.0, 61.0, 0.0));  // the view turned: the table stays
    EXPECT_EQ(r.atmosphere_stats().sky_view_renders, 2);
    // The Sun moved by less than half a step of the table's grid of zenith angles (0.001 degrees):
    // the table stays; once it is nearer the next grid angle, the table is rendered again.
    r.render(ground_snapshot(1.5, 20.0, 61.0003, 0.0));
    EXPECT_EQ(r.atmosphere_stats().sky_view_renders, 2);
    r.render(ground_snapshot(1.5, 20.0, 61.0007, 0.0));
    EXPECT_EQ(r.atmosphere_stats().sky_view_renders, 3);
    EXPECT_EQ(r.atmosphere_stats().passes_marched, 0);
}

TEST(AtmosphereRender, FrustumCullingIsConservative) {
    // A channel whose right edge is straight ahead (right half-angle 0).
    const ChannelFrustum f(EulerDeg{}, FovDeg{45, 0, 20, 20}, 32, 32);
    auto at = [](double yaw_right_deg, double distance) {
        const double a = glm::radians(yaw_right_deg);
        return distance * glm::dvec3(std::sin(a), 0.0, -std::cos(a));
    };
    EXPECT_TRUE(sphere_outside_frustum(f, at(10.0, 100.0), 100.0 * std::sin(glm::radians(9.0))));
    EXPECT_FALSE(sphere_outside_frustum(f, at(10.0, 100.0), 100.0 * std::sin(glm::radians(11.0))));
    EXPECT_FALSE(sphere_outside_frustum(f, at(-30.0, 100.0), 1.0));                  // inside
    EXPECT_TRUE(sphere_outside_frustum(f, glm::dvec3(0.0, 0.0, 100.0), 10.0));       // behind
    EXPECT_FALSE(sphere_outside_frustum(f, glm::dvec3(0.0, 0.0, 5.0), 10.0));        // around the camera
    EXPECT_TRUE(sphere_outside_frustum(f, glm::dvec3(-10.0, 100.0, -100.0), 10.0));  // above
}

TEST(AtmosphereRender, HardCasesStayFinite) {
    context();
    for (const std::string model : {"low", "analytic"}) {
        const SceneConfig scene = make_scene("hard_" + model, model, true);
        ClusterConfig cluster;
        const ChannelConfig wide = channel(48, 32, FovDeg{50, 50, 40, 40});
        SceneRenderer r(cluster, wide, scene);
        const double top = scene.bodies[kEarth].atmosphere.parameters.top_radius - kEarthRadius;
        struct Case {
            std::string name;
            Snapshot snap;
        };
        std::vector<Case> cases;
        // Exactly at the ground and exactly at the top, looking at the horizon, down and up.
        for (double pitch : {0.0, -60.0, 60.0}) {
            cases.push_back({"ground pitch " + std::to_string(pitch), ground_snapshot(0.0, pitch, 70.0, 20.0, 3)});
            cases.push_back({"top pitch " + std::to_string(pitch), ground_snapshot(top, pitch, 70.0, 20.0, 3)});
        }
        // The Sun on the horizon, ahead, and a 1 m rock 4 m in front of a camera 1.5 m up.
        Snapshot rock = ground_snapshot(1.5, 0.0, 90.0, 0.0, 3);
        rock.bodies[kRock].position_m = rock.camera_position_m + glm::dvec3(4.0, 0.0, 0.0);
        cases.push_back({"rock at sunset", rock});
        for (auto& c : cases)
            if (c.name != "rock at sunset")  // the rock far away, out of the way
                c.snap.bodies[kRock].position_m = glm::dvec3(0.0, 0.0, -1.0e9);
        // 1 AU from the Earth, looking at it: a wide channel (the Earth under a pixel) and one
        // 0.01 degrees wide (the Earth fills half of it).
        Snapshot far = ground_snapshot(0.0, 0.0, 90.0, 90.0, 3);
        far.camera_position_m = glm::dvec3(-kAu, 0.0, 0.0);              // looking along +X at the Earth
        far.bodies[kSun].position_m = glm::dvec3(-kAu, 0.2 * kAu, 0.0);  // out of view, the Earth nearly full
        far.bodies[kRock].position_m = glm::dvec3(0.0, 0.0, -1.0e9);
        cases.push_back({"1 AU", far});
        for (const auto& c : cases) {
            const Image img = r.render(c.snap);
            EXPECT_EQ(bad_pixels(img), 0) << model << ": " << c.name;
            if (c.name == "1 AU") {  // the Earth under a pixel: its point (passes/planet_light, with_air), not its air
                double peak = 0.0;
                for (int y = 0; y < img.height; ++y)
                    for (int x = 0; x < img.width; ++x) peak = std::max(peak, double(img.pixel(x, y)[1]));
                EXPECT_GT(peak, 0.0) << model << ": the Earth's point at 1 AU";
            }
            if (c.name == "rock at sunset") {
                // The rock's night side (it is lit from behind) gets the air of its 3 m only,
                // which needs its distance from the geometry: far darker than the evening sky.
                const double sky = std::max(img.pixel(2, 12)[1], img.pixel(45, 12)[1]);
                EXPECT_GT(sky, 0.0) << model;
                EXPECT_LT(img.pixel(24, 15)[1], 1e-2 * sky) << model;
            }
        }
        SceneRenderer narrow(cluster, channel(32, 32, FovDeg{0.005, 0.005, 0.005, 0.005}), scene);
        const Image img = narrow.render(far);
        EXPECT_EQ(bad_pixels(img), 0) << model << ": 1 AU, narrow";
        EXPECT_GT(img.pixel(16, 16)[1], 0.0f) << model << ": the Earth's day side at 1 AU";
        // Every case draws its air but the Earth at 1 AU in the wide channel, a point there.
        EXPECT_EQ(r.atmosphere_stats().passes_run, static_cast<long>(cases.size()) - 1);
    }
}

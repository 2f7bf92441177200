// Rendered eclipse checks: real loopback runs (master + slave processes, UDP, EGL,
// EXR and PNG files, stitched domemasters kept under build/test-tmp/EclipseRender_*-<hash>/out/dome).
//   - From the ground at the greatest-eclipse point of 2006-03-29 (the point and instant come
//     from our own prediction, scene/eclipse_geometry.hpp): the sky at 90 % obscuration and in
//     totality, against the same sky with shadows off. The sky's mean luminance follows the
//     observer's visible fraction, totality is darker again, the zenith agrees with the CPU
//     build of the same shading code, and the corona shows only in totality.
//   - From space above that point: the umbra on the Earth in exact mode, and the whole penumbra
//     tinted in illustrative mode.
//   - The Moon in the total lunar eclipse of 2022-11-08: dark and red.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "atmosphere/production_model.hpp"
#include "atmosphere/production_quality.hpp"
#include "config/scene_config.hpp"
#include "eclipse/eclipse_reference.hpp"
#include "eclipse/shadow_casters.hpp"
#include "image/frame_image.hpp"
#include "scene/eclipse_geometry.hpp"
#include "scene/sim_time.hpp"
#include "shading/shared_shading.hpp"
#include "show_script.hpp"
#include "support/cluster_fixture.hpp"
#include "support/loopback_run.hpp"
#include "util/child_process.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// Linear radiance of a frame (EXR values divided by the exposure they were written with).
Image read_frame(const std::string& dir, int frame) {
    FrameMetadata meta;
    Image img = read_image_radiance(dir + "/" + frame_file_name(frame, "exr"), &meta);
    for (float& v : img.rgba) {
        EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
        v /= meta.exposure;
    }
    return img;
}

// The brightest pixel's position (x, y).
glm::ivec2 brightest_pixel(const Image& img) {
    int best = 0;
    for (int i = 1; i < img.width * img.height; ++i)
        if (luminance(&img.rgba[4 * i]) > luminance(&img.rgba[4 * best])) best = i;
    return {best % img.width, best / img.width};
}

// Mean luminance of the pixels whose centre lies between r0 and r1 pixels from (cx, cy).
double ring_luminance(const Image& img, double cx, double cy, double r0, double r1) {
    double s = 0.0;
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double r = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
            if (r >= r0 && r < r1) s += luminance(img.pixel(x, y)), ++n;
        }
    EXPECT_GT(n, 0);
    return n ? s / n : 0.0;
}

std::string utc_of(double t_tt) { return tt_to_utc_iso(t_tt); }

// The apparent discs of the Sun and the Moon seen from a point, in double; visible fraction by
// the double-precision reference.
double visible_fraction_from(const Snapshot& snap, const SceneConfig& scene, const glm::dvec3& p) {
    const auto sun = scene.find("sun"), moon = scene.find("moon");
    glm::dvec3 ps{}, pm{};
    for (const auto& b : snap.bodies) {
        if (b.id == sun->id) ps = b.position_m;
        if (b.id == moon->id) pm = b.position_m;
    }
    const glm::dvec3 us = glm::normalize(ps - p), um = glm::normalize(pm - p);
    const double rs = std::asin(sun->radius_m / glm::length(ps - p));
    const double rm = std::asin(moon->radius_m / glm::length(pm - p));
    const double sep = 2.0 * std::asin(0.5 * glm::length(us - um));
    return eclipse::visible_fraction_reference(rm / rs, sep / rs, sun->limb_darkening_u);
}

struct Site {
    double lat_deg, lon_deg, alt_m;
};

Snapshot observer_snapshot(const SceneConfig& scene, double t, const Site& site, double azimuth_deg = 180.0) {
    ShowKeyframe k;
    k.sim_time_s = t;
    k.camera.anchor = scene.find("earth")->id;
    k.camera.observer = ObserverSite{site.lat_deg, site.lon_deg, site.alt_m, azimuth_deg, 0.0};
    return ShowScript({k}, 1.0).evaluate(0.0, scene);
}

glm::dvec3 position_of(const Snapshot& snap, uint16_t id) {
    for (const auto& b : snap.bodies)
        if (b.id == id) return b.position_m;
    return {};
}

using test::run_loopback;

nlohmann::json keyframe(double at_s, double t_tt, const nlohmann::json& camera, const std::string& mode) {
    return {{"at_s", at_s}, {"time_utc", utc_of(t_tt)}, {"camera", camera}, {"shadow_mode", mode}};
}

// One channel of a test cluster: square, `half_fov_deg` each way, pitched up from the camera's
// forward direction.
nlohmann::json test_channel(int id, const std::string& name, double pitch_deg, int port, double half_fov_deg) {
    return {{"id", id},
            {"name", name},
            {"orientation", {{"pitch_deg", pitch_deg}}},
            {"unicast_address", "127.0.0.1:" + std::to_string(port)},
            {"fov",
             {{"left_deg", half_fov_deg},
              {"right_deg", half_fov_deg},
              {"up_deg", half_fov_deg},
              {"down_deg", half_fov_deg}}}};
}

// A unicast loopback cluster on the physical scene with the show in `dir`, n x n channels,
// EXR + PNG frames at a fixed exposure (run_loopback adds the key and the timeouts).
nlohmann::json test_cluster(int id, const std::string& dir, int report_port, int n, int dome_size, double exposure,
                            const nlohmann::json& channels) {
    return {{"cluster_id", id},
            {"scene", test::source_path("configs/scenes/earth-physical.json")},
            {"show", dir + "/show.json"},
            {"network", {{"transport", "unicast"}, {"master_address", "127.0.0.1"}, {"report_port", report_port}}},
            {"dome", {{"fov_deg", 180}, {"tilt_deg", 0}, {"require_full_coverage", false}}},
            {"output",
             {{"width", n},
              {"height", n},
              {"formats", {"exr", "png"}},
              {"domemaster_size", dome_size},
              {"exposure", exposure}}},
            {"channels", channels}};
}

const SceneConfig& physical_scene() {
    static const SceneConfig s = load_scene_config(test::source_path("configs/scenes/earth-physical.json"));
    return s;
}

}  // namespace

TEST(EclipseRender, GroundTotalityDarkensTheSkyWithTheVisibleFractionAndShowsTheCorona) {
    const SceneConfig& scene = physical_scene();
    const EclipseEvent ev = next_solar_eclipse(utc_iso_to_j2000_seconds("2006-03-25T00:00:00Z"));
    ASSERT_EQ(ev.type, "total");
    const Site site{ev.lat_deg, ev.lon_deg, 2.0};
    const double t_tot = ev.peak_tt_s;

    // The observer's visible fraction (double reference): 0 in totality; 0.1 (90 % of the
    // limb-darkened light hidden) some minutes before, found by bisection.
    auto fraction_at = [&](double t) {
        const Snapshot s = observer_snapshot(scene, t, site);
        return visible_fraction_from(s, scene, s.camera_position_m);
    };
    ASSERT_EQ(fraction_at(t_tot), 0.0);
    double lo = t_tot - 3600.0, hi = t_tot;
    ASSERT_GT(fraction_at(lo), 0.5);
    for (int i = 0; i < 40; ++i) ((fraction_at(0.5 * (lo + hi)) > 0.1) ? lo : hi) = 0.5 * (lo + hi);
    const double t_90 = 0.5 * (lo + hi);
    const double f_90 = fraction_at(t_90);
    ASSERT_NEAR(f_90, 0.1, 1e-3);
    std::printf("greatest eclipse %s at %.4f, %.4f; 90 %% obscuration at %s (%.0f s before)\n", utc_of(t_tot).c_str(),
                site.lat_deg, site.lon_deg, utc_of(t_90).c_str(), t_tot - t_90);

    // Face the Sun's azimuth at the horizon: the dome's apex is the zenith, the "sun" channel
    // pitches up to the Sun's altitude, the "sky" channel looks at the zenith.
    const Snapshot probe = observer_snapshot(scene, t_tot, site);
    const glm::dvec3 earth = position_of(probe, scene.find("earth")->id);
    const glm::dvec3 zenith = glm::normalize(probe.camera_position_m - earth);
    const glm::dvec3 to_sun = glm::normalize(position_of(probe, scene.find("sun")->id) - probe.camera_position_m);
    const glm::dvec3 pole = glm::mat3_cast(probe.bodies[scene.find("earth")->id].orientation) * glm::dvec3(0, 0, 1);
    const glm::dvec3 north = glm::normalize(pole - zenith * glm::dot(pole, zenith));
    const glm::dvec3 east = glm::cross(north, zenith);
    const double alt_deg = glm::degrees(std::asin(glm::dot(to_sun, zenith)));
    const double az_deg = glm::degrees(std::atan2(glm::dot(to_sun, east), glm::dot(to_sun, north)));
    std::printf("the Sun at azimuth %.2f deg, altitude %.2f deg\n", az_deg, alt_deg);
    ASSERT_GT(alt_deg, 30.0);

    const std::string dir = test::scratch_dir("EclipseRender_ground");
    const nlohmann::json camera = {{"anchor", "earth"},
                                   {"observer", {{"lat_deg", site.lat_deg}, {"lon_deg", site.lon_deg}, {"alt_m", 2.0}}},
                                   {"look_azimuth_deg", az_deg}};
    const nlohmann::json show = {
        {"frame_interval_s", 1.0},
        {"keyframes",
         {keyframe(0, t_tot, camera, "off"), keyframe(1, t_90, camera, "exact"), keyframe(2, t_tot, camera, "exact")}}};
    test::write_text(dir + "/show.json", show.dump(2));
    const int n = 64;
    const double sun_half_fov = 4.0;
    const nlohmann::json cluster =
        test_cluster(4301, dir, 47901, n, 128, 1e-4,
                     nlohmann::json::array({test_channel(0, "sky", 90.0, 47900, 60.0),
                                            test_channel(1, "sun", alt_deg, 47902, sun_half_fov)}));
    const std::string out = run_loopback(dir, cluster, 3);
    for (int f = 0; f < 3; ++f) EXPECT_TRUE(std::filesystem::exists(out + "/dome/" + frame_file_name(f, "png")));

    const Image sky_off = read_frame(out + "/sky", 0), sky_90 = read_frame(out + "/sky", 1),
                sky_tot = read_frame(out + "/sky", 2);
    // The sky's light: away from the Sun, which in this channel (1.9 degrees a pixel) is a point
    // carrying its visible part's light, far brighter than the sky around it.
    const glm::ivec2 sun_px = brightest_pixel(sky_off);
    const auto sky_luminance = [&](const Image& img) {
        return ring_luminance(img, sun_px.x + 0.5, sun_px.y + 0.5, 4.0, 2.0 * n);
    };
    const double l_off = sky_luminance(sky_off), l_90 = sky_luminance(sky_90), l_tot = sky_luminance(sky_tot);
    std::printf(
        "mean sky luminance: no eclipse %.4g, 90 %% %.4g (ratio %.4f, visible fraction %.4f), totality %.4g "
        "(%.4f of 90 %%)\n",
        l_off, l_90, l_90 / l_off, f_90, l_tot, l_tot / l_90);
    ASSERT_GT(l_off, 0.0);
    // At 90 % the air around the observer is lit by about the observer's visible fraction.
    EXPECT_NEAR(l_90 / l_off / f_90, 1.0, 0.3);
    // In totality the sky overhead lies in the umbra: only air outside it still scatters light.
    EXPECT_GT(l_tot, 0.0);
    EXPECT_LT(l_tot / l_90, 0.5);

    // The zenith pixel against the CPU build of the same code (production model, shadowed march).
    const atmosphere::ProductionAtmosphere model(scene.find("earth")->atmosphere.parameters,
                                                 atmosphere::production_quality("medium"));
    sh::Texture2DData dummy{1, 1, {glm::vec4(1.0f)}};
    ShadowCasting casting(scene, {});
    auto cpu_zenith = [&](double t, ShadowMode mode) {
        Snapshot s = observer_snapshot(scene, t, site);
        s.settings.flags = with_shadow_mode(0, mode);
        const glm::dvec3 e = position_of(s, scene.find("earth")->id);
        const glm::dvec3 rel = s.camera_position_m - e;
        const glm::vec3 v(glm::normalize(rel));
        const glm::vec3 sun(glm::normalize(position_of(s, scene.find("sun")->id) - e));
        const sh::AtmosphereParams& a = model.shader_params();
        const sh::AtmosphereRayStart st = sh::atm_ray_start(a, static_cast<float>(glm::length(rel)), v, -v, sun);
        const sh::EclipseCasters c = casting.casters_for(s, scene.find("earth")->id, glm::dmat3(1.0));
        const auto& tb = model.tables();
        const sh::EclipseRay ray = sh::eclipse_ray(c, glm::vec2(1.0f), glm::vec3(rel) + v * st.offset_m, v);
        const sh::AtmosphereSegment seg = sh::atm_view_ray_shadowed(
            a, sh::sampler2D{&tb.transmittance}, glm::vec2(tb.transmittance.width, tb.transmittance.height),
            sh::sampler2D{&tb.multiple_scattering},
            glm::vec2(tb.multiple_scattering.width, tb.multiple_scattering.height), model.quality().multiple_scattering,
            st, -1.0f, model.quality().view_samples, ray, sh::sampler2D{&dummy});
        return model.to_xyz(seg.inscatter_per_sr).y;
    };
    const double z_off = cpu_zenith(t_tot, ShadowMode::Off), z_90 = cpu_zenith(t_90, ShadowMode::Exact),
                 z_tot = cpu_zenith(t_tot, ShadowMode::Exact);
    auto gpu_zenith = [&](const Image& img) {
        double s = 0.0;
        for (int y = n / 2 - 1; y <= n / 2; ++y)
            for (int x = n / 2 - 1; x <= n / 2; ++x) s += luminance(img.pixel(x, y));
        return s / 4.0;
    };
    std::printf("zenith 90%%/off: GPU %.4f CPU %.4f; totality/off: GPU %.3g CPU %.3g\n",
                gpu_zenith(sky_90) / gpu_zenith(sky_off), z_90 / z_off, gpu_zenith(sky_tot) / gpu_zenith(sky_off),
                z_tot / z_off);
    EXPECT_NEAR((gpu_zenith(sky_90) / gpu_zenith(sky_off)) / (z_90 / z_off), 1.0, 0.1);
    // In totality the zenith ray lies wholly in the umbra: no sunlit air, on either side.
    EXPECT_LE(gpu_zenith(sky_tot), 1e-6 * gpu_zenith(sky_off));
    EXPECT_LE(z_tot, 1e-6 * z_off);

    // The corona: the ring 1.3-2.5 solar radii against the ring 4.5-5.5 radii around the Sun
    // (the centre of the "sun" channel). Drowned at 90 %, bright in totality.
    const double px_per_rad = n / (2.0 * std::tan(glm::radians(sun_half_fov)));
    const double r_sun_px = std::tan(std::asin(scene.find("sun")->radius_m / 1.495978707e11)) * px_per_rad;
    auto corona_contrast = [&](const Image& img) {
        return ring_luminance(img, n / 2.0, n / 2.0, 1.3 * r_sun_px, 2.5 * r_sun_px) /
               ring_luminance(img, n / 2.0, n / 2.0, 4.5 * r_sun_px, 5.5 * r_sun_px);
    };
    const Image sun_90 = read_frame(out + "/sun", 1), sun_tot = read_frame(out + "/sun", 2);
    std::printf("corona contrast (inner / outer ring): 90 %% %.3f, totality %.3f\n", corona_contrast(sun_90),
                corona_contrast(sun_tot));
    EXPECT_LT(corona_contrast(sun_90), 1.5);
    EXPECT_GT(corona_contrast(sun_tot), 3.0);
    // The Moon covers the disc: the centre is darker than the corona around it.
    EXPECT_LT(luminance(sun_tot.pixel(n / 2, n / 2)),
              ring_luminance(sun_tot, n / 2.0, n / 2.0, 1.3 * r_sun_px, 2.5 * r_sun_px));
}

namespace {
// The view ray through a pixel centre (image row 0 at the top) of a channel looking along the
// camera's -Z, in the world frame.
glm::dvec3 pixel_ray(const Snapshot& snap, int x, int y, int n, double half_fov_deg) {
    const double t = std::tan(glm::radians(half_fov_deg));
    const sh::vec3 v = sh::channel_ray(sh::vec2(x + 0.5f, n - 1 - y + 0.5f), sh::vec2(n, n), sh::vec4(t, t, t, t));
    return glm::mat3_cast(snap.camera_orientation) * glm::dvec3(v);
}
}  // namespace

TEST(EclipseRender, FromSpaceTheUmbraDarkensTheEarthAndIllustrativeModeShowsTheWholePenumbra) {
    const SceneConfig& scene = physical_scene();
    const EclipseEvent ev = next_solar_eclipse(utc_iso_to_j2000_seconds("2006-03-25T00:00:00Z"));
    const double t = ev.peak_tt_s;
    const double half_fov = 45.0;  // the whole Earth from 4000 km; the umbra spans a few pixels
    const int n = 96;
    const nlohmann::json camera = {{"anchor", "earth"},
                                   {"observer", {{"lat_deg", ev.lat_deg}, {"lon_deg", ev.lon_deg}, {"alt_m", 4.0e6}}},
                                   {"look_at", "earth"}};
    const std::string dir = test::scratch_dir("EclipseRender_space");
    const nlohmann::json show = {{"frame_interval_s", 1.0},
                                 {"keyframes",
                                  {keyframe(0, t, camera, "off"), keyframe(1, t + 1e-3, camera, "exact"),
                                   keyframe(2, t + 2e-3, camera, "illustrative")}}};
    test::write_text(dir + "/show.json", show.dump(2));
    const nlohmann::json cluster = test_cluster(
        4302, dir, 47906, n, 128, 1e-4, nlohmann::json::array({test_channel(0, "earth", 0.0, 47905, half_fov)}));
    const std::string out = run_loopback(dir, cluster, 3);
    const Image off = read_frame(out + "/earth", 0), exact = read_frame(out + "/earth", 1),
                ill = read_frame(out + "/earth", 2);

    // The camera hangs over the greatest-eclipse point: the umbra is in the middle of the view.
    const double centre_off = luminance(off.pixel(n / 2, n / 2)), centre_exact = luminance(exact.pixel(n / 2, n / 2));
    std::printf("centre: no eclipse %.4g, exact %.4g (%.4f)\n", centre_off, centre_exact, centre_exact / centre_off);
    EXPECT_LT(centre_exact / centre_off, 0.05);
    // Per day-side pixel: the region our CPU geometry predicts (double, ray-sphere on the
    // rendered Earth) against what the illustrative render tinted.
    Snapshot snap = ShowScript::load(dir + "/show.json", scene).evaluate(0.0, scene);
    const auto& earth = *scene.find("earth");
    const glm::dvec3 ce = position_of(snap, earth.id), cs = position_of(snap, scene.find("sun")->id),
                     cm = position_of(snap, scene.find("moon")->id);
    double max_off = 0.0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) max_off = std::max(max_off, luminance(off.pixel(x, y)));
    int agree = 0, total = 0, predicted_penumbra = 0, tinted = 0, darkened_exact = 0;
    int umbra_px = 0, umbra_red = 0, penumbra_px = 0, penumbra_yellow = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            if (luminance(off.pixel(x, y)) < 0.1 * max_off) continue;  // night side or space
            const glm::dvec3 v = pixel_ray(snap, x, y, n, half_fov);
            const glm::dvec3 oc = snap.camera_position_m - ce;
            const double b = glm::dot(oc, v), c = glm::dot(oc, oc) - earth.radius_m * earth.radius_m;
            if (b * b - c <= 0.0) continue;  // atmosphere only
            const glm::dvec3 p = snap.camera_position_m + v * (-b - std::sqrt(b * b - c));
            const glm::dvec3 us = glm::normalize(cs - p), um = glm::normalize(cm - p);
            const double rs = std::asin(scene.find("sun")->radius_m / glm::length(cs - p));
            const double a = std::asin(scene.find("moon")->radius_m / glm::length(cm - p)) / rs;
            const double s = 2.0 * std::asin(0.5 * glm::length(us - um)) / rs;
            const bool in_shadow = s < 1.0 + a;
            const float* po = off.pixel(x, y);
            const float* pi = ill.pixel(x, y);
            const bool is_tinted = std::fabs(pi[2] / po[2] - 1.0) > 0.05 || std::fabs(pi[0] / po[0] - 1.0) > 0.05;
            ++total;
            agree += in_shadow == is_tinted;
            predicted_penumbra += in_shadow;
            tinted += is_tinted;
            darkened_exact += luminance(exact.pixel(x, y)) < 0.95 * luminance(po);
            // The region tints: the umbra's (0.85, 0.12, 0.10) takes far more green than red off,
            // the penumbra's (1, 0.85, 0.3) most of the blue and no red.
            const double drop_r = 1.0 - pi[0] / po[0], drop_g = 1.0 - pi[1] / po[1], drop_b = 1.0 - pi[2] / po[2];
            if (s < a - 1.0) {
                ++umbra_px;
                umbra_red += drop_g > 2.0 * drop_r;
            } else if (in_shadow && s > std::fabs(1.0 - a) + 0.1) {
                ++penumbra_px;
                penumbra_yellow += drop_b > 2.0 * drop_g && drop_r < 0.01;
            }
        }
    std::printf(
        "day-side pixels %d: predicted in the penumbra %d, tinted (illustrative) %d, darkened by > 5 %% "
        "(exact) %d, agreement %.3f\n",
        total, predicted_penumbra, tinted, darkened_exact, double(agree) / total);
    std::printf("umbra pixels %d (%d tinted red), penumbra pixels %d (%d tinted yellow)\n", umbra_px, umbra_red,
                penumbra_px, penumbra_yellow);
    ASSERT_GT(total, 500);
    EXPECT_GE(umbra_red, umbra_px * 9 / 10);
    ASSERT_GT(penumbra_px, 50);
    EXPECT_GE(penumbra_yellow, penumbra_px * 9 / 10);
    ASSERT_GT(predicted_penumbra, 50);
    EXPECT_GT(double(agree) / total, 0.95);
    // The penumbra's faint outer part barely darkens in exact mode; illustrative shows all of it.
    EXPECT_GT(tinted, darkened_exact);
}

TEST(EclipseRender, TheMoonTurnsDarkAndRedInATotalLunarEclipse) {
    const SceneConfig& scene = physical_scene();
    const EclipseEvent ev = next_lunar_eclipse(utc_iso_to_j2000_seconds("2022-11-01T00:00:00Z"));
    ASSERT_EQ(ev.type, "total");
    const Snapshot probe = observer_snapshot(scene, ev.peak_tt_s, Site{0, 0, 0});
    const glm::dvec3 e = position_of(probe, scene.find("earth")->id), m = position_of(probe, scene.find("moon")->id);
    const glm::dvec3 offset = glm::normalize(m - e) * 3.0e7;  // beyond the Earth's air, towards the Moon
    const nlohmann::json camera = {
        {"anchor", "earth"}, {"offset_m", {offset.x, offset.y, offset.z}}, {"look_at", "moon"}};
    const std::string dir = test::scratch_dir("EclipseRender_lunar");
    const nlohmann::json show = {
        {"frame_interval_s", 1.0},
        {"keyframes", {keyframe(0, ev.peak_tt_s, camera, "off"), keyframe(1, ev.peak_tt_s + 1e-3, camera, "exact")}}};
    test::write_text(dir + "/show.json", show.dump(2));
    const int n = 48;
    const nlohmann::json cluster =
        test_cluster(4303, dir, 47911, n, 64, 1.0, nlohmann::json::array({test_channel(0, "moon", 0.0, 47910, 0.5)}));
    const std::string out = run_loopback(dir, cluster, 2);
    const Image off = read_frame(out + "/moon", 0), ecl = read_frame(out + "/moon", 1);
    double sum_off[3] = {}, sum_ecl[3] = {};
    for (int y = n / 2 - 4; y < n / 2 + 4; ++y)
        for (int x = n / 2 - 4; x < n / 2 + 4; ++x)
            for (int k = 0; k < 3; ++k) sum_off[k] += off.pixel(x, y)[k], sum_ecl[k] += ecl.pixel(x, y)[k];
    const double dim = (sum_ecl[1] + sum_ecl[0]) / (sum_off[1] + sum_off[0]);
    const double red_off = sum_off[0] / sum_off[2], red_ecl = sum_ecl[0] / sum_ecl[2];
    std::printf("Moon at totality: brightness %.3g of the full Moon; red/blue %.2f (full Moon %.2f)\n", dim, red_ecl,
                red_off);
    EXPECT_LT(dim, 1e-2);
    EXPECT_GT(dim, 0.0);
    EXPECT_GT(red_ecl, 3.0 * red_off);
}

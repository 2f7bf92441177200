// The moonlit sky (common/atmosphere/moonlit_sky.hpp, slave/passes/moonlight.hpp,
// shaders/atmosphere_lookup.frag SKY_MOON): the air
// lit by the Moon as a second source through the Sun's tables.
//   - The production model's moonlit sky against the empirical model of Krisciunas & Schaefer
//     1991 (their equations 15-21, fitted to Mauna Kea V-band data), on a grid of Moon phases and
//     positions and view directions, with K&S's extinction coefficient taken from the model's own
//     zenith transmittance: the error in magnitudes, printed and bounded.
//   - The rule that decides, once per frame, whether the Moon's light is drawn: never by day, at
//     night with the Moon up, never from space.
//   - Rendered: the Moon's part of a night frame (with it up, minus with it set) is the frame with
//     the Sun where the Moon is, times the Moon's irradiance over the Sun's from its phase curve,
//     pixel by pixel: the same tables, the Moon's azimuth and scale plumbed right.
//   - Two half channels equal one wide channel (no seam).
//   - The master's automatic exposure sees the Moon's sky: the planets-tonight night under its
//     68 % Moon is exposed for it, the same night with the Moon set is not, and by day the Moon
//     changes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "atmosphere/auto_exposure.hpp"
#include "atmosphere/production_model.hpp"
#include "atmosphere/solar_scale.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "master_node.hpp"
#include "atmosphere/moonlit_sky.hpp"
#include "scene/planet_magnitude.hpp"
#include "scene_renderer.hpp"
#include "show_script.hpp"
#include "support/headless_gl.hpp"
#include "support/planet_frames.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {
constexpr double kR = 6.371e6, kAu = 1.496e11, kMoonDistance = 3.844e8;
constexpr double kNanolambert_cd_m2 = 1e-9 * 1e4 / 3.14159265358979;  // 1 L = 10^4 / pi cd/m^2
constexpr double kZeroMagLux = 2.54e-6;                               // V = 0 (the scenes' zero_mag_flux)

const atmosphere::ProductionAtmosphere& earth_air() {
    static const atmosphere::ProductionAtmosphere m = [] {
        const SceneConfig scene = load_scene_config(test::source_path("configs/scenes/solar-system.json"));
        const BodyConfig& earth = *scene.find("earth");
        return atmosphere::ProductionAtmosphere(earth.atmosphere.parameters,
                                                atmosphere::production_quality(earth.atmosphere.model));
    }();
    return m;
}

glm::dvec3 local_direction(double zenith_deg, double azimuth_deg) {
    const double z = glm::radians(zenith_deg), a = glm::radians(azimuth_deg);
    return {std::sin(z) * std::cos(a), std::sin(z) * std::sin(a), std::cos(z)};
}

double airmass_ks(double zenith_deg) {  // K&S 1991, equation 3
    const double s = std::sin(glm::radians(zenith_deg));
    return 1.0 / std::sqrt(1.0 - 0.96 * s * s);
}

// Krisciunas & Schaefer 1991, equations 15, 20 and 21: the moonlit sky's V-band brightness in
// nanolamberts, the Moon at phase angle alpha and zenith angle z_moon, the view at zenith angle z
// and rho from the Moon, k the extinction coefficient (mag per airmass).
double ks_moonlit_sky_nl(double alpha_deg, double rho_deg, double z_moon_deg, double z_deg, double k) {
    const double moon = std::pow(10.0, -0.4 * (3.84 + 0.026 * alpha_deg + 4e-9 * std::pow(alpha_deg, 4.0)));
    const double c = std::cos(glm::radians(rho_deg));
    const double scattering = std::pow(10.0, 5.36) * (1.06 + c * c) + std::pow(10.0, 6.15 - rho_deg / 40.0);
    return scattering * moon * std::pow(10.0, -0.4 * k * airmass_ks(z_moon_deg)) *
           (1.0 - std::pow(10.0, -0.4 * k * airmass_ks(z_deg)));
}

// The Moon's V at phase angle alpha, at its mean distance and 1 AU from the Sun (Allen's law).
double moon_v(double alpha_deg, double distance_m = kMoonDistance) {
    PlanetGeometry g;
    g.observer_distance_au = distance_m / kAu;
    g.phase_deg = alpha_deg;
    return *planet_magnitude_v("moon", g);
}
}  // namespace

TEST(MoonlitSky, TheModelsMoonlitSkyAgreesWithKrisciunasAndSchaefer) {
    const atmosphere::ProductionAtmosphere& m = earth_air();
    const double d = m.shader_params().bottom_radius_m + 150.0;
    glm::dvec3 t_zenith;
    sky_luminance(m, d, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), &t_zenith);
    const double k = -2.5 * std::log10(t_zenith.y);  // at 550 nm, the V band's middle
    const double per_phys = 1.0 / atmosphere::physical_solar_illuminance(m);
    std::printf("extinction k = %.3f mag/airmass (K&S measured 0.172 on Mauna Kea)\n", k);
    double worst = 0.0, sum2 = 0.0;
    int n = 0;
    for (const double alpha : {0.0, 45.0, 90.0})
        for (const double z_moon : {30.0, 60.0})
            for (const double z : {0.0, 30.0, 60.0})
                for (const double az : {0.0, 90.0, 180.0}) {
                    const glm::dvec3 moon = local_direction(z_moon, 0.0), view = local_direction(z, az);
                    const double rho = glm::degrees(std::acos(glm::dot(moon, view)));
                    if (rho < 10.0) continue;  // K&S's fit holds from 10 degrees out
                    const double e_moon = kZeroMagLux * std::pow(10.0, -0.4 * moon_v(alpha));
                    const double ours = sky_luminance(m, d, view, moon) * per_phys * e_moon;
                    const double theirs = ks_moonlit_sky_nl(alpha, rho, z_moon, z, k) * kNanolambert_cd_m2;
                    const double dmag = -2.5 * std::log10(ours / theirs);
                    std::printf(
                        "alpha %2.0f  Moon z %2.0f  view z %2.0f az %3.0f (rho %5.1f): %.3g vs %.3g cd/m^2, %+.2f "
                        "mag\n",
                        alpha, z_moon, z, az, rho, ours, theirs, dmag);
                    worst = std::max(worst, std::abs(dmag));
                    sum2 += dmag * dmag;
                    ++n;
                }
    std::printf("%d points: worst %.2f mag, rms %.2f mag\n", n, worst, std::sqrt(sum2 / n));
    EXPECT_GT(n, 40);
    EXPECT_LT(worst, 0.75);
    EXPECT_LT(std::sqrt(sum2 / n), 0.4);
}

namespace {
// A full Moon's light for moon_on_air: its irradiance over the Sun's from its phase curve.
SkySecondLight full_moon(const glm::dvec3& position_m, double sun_irradiance) {
    SkySecondLight l;
    l.present = true;
    l.position_m = position_m;
    l.irradiance_rgb = glm::dvec3(sun_irradiance * std::pow(10.0, -0.4 * (moon_v(5.0) - kSunMagnitudeV)));
    return l;
}
}  // namespace

TEST(MoonlitSky, TheMoonsLightIsDrawnAtNightWithTheMoonUpNeverByDayNorFromSpace) {
    const atmosphere::ProductionAtmosphere& m = earth_air();
    const glm::dvec3 planet(0.0), ground(0.0, 0.0, kR + 150.0);
    const glm::dvec3 moon = ground + kMoonDistance * local_direction(50.0, 0.0);
    const double e_sun = 1.0;
    auto on = [&](double sun_altitude_deg, const glm::dvec3& camera, const glm::dvec3& moon_m) {
        const glm::dvec3 sun = local_direction(90.0 - sun_altitude_deg, 180.0);
        return moon_on_air(full_moon(moon_m, e_sun), camera, planet, sun, e_sun, m).on;
    };
    EXPECT_FALSE(on(10.0, ground, moon)) << "by day";
    EXPECT_FALSE(on(0.0, ground, moon)) << "at sunset";
    EXPECT_TRUE(on(-12.0, ground, moon)) << "at the end of nautical twilight";
    EXPECT_TRUE(on(-30.0, ground, moon)) << "at night";
    EXPECT_FALSE(on(-30.0, glm::dvec3(0.0, 0.0, 2.0 * kR), moon)) << "from space";
    EXPECT_FALSE(on(-30.0, ground, ground + kMoonDistance * local_direction(140.0, 0.0))) << "the Moon set";
    EXPECT_FALSE(moon_on_air(SkySecondLight{}, ground, planet, local_direction(120.0, 180.0), e_sun, m).on)
        << "no Moon";
    // Where it is drawn, its share of the zenith sky passes the threshold; where not, it does not.
    const double d = glm::length(ground);
    const double share_day = std::pow(10.0, -0.4 * (moon_v(5.0) - kSunMagnitudeV)) *
                             zenith_sky_luminance(m, d, std::cos(glm::radians(50.0))) /
                             zenith_sky_luminance(m, d, std::cos(glm::radians(80.0)));
    std::printf("a full Moon's share of the zenith sky with the Sun 10 degrees up: %.2g\n", share_day);
    EXPECT_LT(share_day, kMoonlitSkyMinShare);
}

namespace {
EglContext& context() { return test::headless_gl("MoonlitSky"); }

SceneConfig moon_scene() {
    const std::string dir = test::scratch_dir("MoonlitSky");
    test::write_text(dir + "/scene.json", R"({ "bodies": [
        { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 2.0e9, "limb_darkening_u": 0.6 },
        { "name": "earth", "kind": "planet", "ephemeris": "earth", "radius_m": 6.371e6, "albedo": 0.3, "texture": "generated:earth",
          "atmosphere": { "preset": "earth", "model": "sky-view" } },
        { "name": "moon", "kind": "moon", "ephemeris": "moon", "radius_m": 1.7374e6, "albedo": 0.12 } ],
      "stars": { "catalog": ")" + test::source_path("data/stars/bright_stars.csv") +
                                              R"(", "magnitude_limit": -2.0, "zero_mag_flux": 2.54e-6 } })");
    return load_scene_config(dir + "/scene.json");
}

// The camera 2 m up at the Earth's +z point, facing world +x (its right is world -y), the Sun
// and the Moon along the given world directions (the Sun 1 AU from the Earth, the Moon at its mean
// distance from the camera).
Snapshot moon_night(const glm::dvec3& sun_dir, const glm::dvec3& moon_dir) {
    Snapshot s;
    s.bodies.resize(3);
    for (uint16_t i = 0; i < 3; ++i) s.bodies[i].id = i;
    s.camera_position_m = glm::dvec3(0.0, 0.0, kR + 2.0);
    s.bodies[0].position_m = kAu * sun_dir;
    s.bodies[2].position_m = s.camera_position_m + kMoonDistance * moon_dir;
    // The Earth turned so that its north pole (where its map is singular) lies on the horizon.
    s.bodies[1].orientation = glm::angleAxis(glm::radians(90.0), glm::dvec3(0.0, 1.0, 0.0));
    s.camera_orientation = glm::quat_cast(glm::dmat3(glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1), glm::dvec3(-1, 0, 0)));
    return s;
}

// Toward the camera's left (world +y), 40 degrees up; the Sun 30 degrees down on the other side:
// the Moon 10 degrees from full, out of the channels' view.
const glm::dvec3 kMoonUp = glm::normalize(glm::dvec3(0.0, std::cos(glm::radians(40.0)), std::sin(glm::radians(40.0))));
const glm::dvec3 kSunDown =
    glm::normalize(glm::dvec3(0.0, -std::cos(glm::radians(30.0)), -std::sin(glm::radians(30.0))));

ClusterConfig one_channel(const ChannelConfig& ch) {
    ClusterConfig c;
    c.channels.push_back(ch);
    return c;
}
}  // namespace

TEST(MoonlitSky, TheMoonsPartIsTheSunsSkyFromTheMoonsPlaceTimesItsIrradiance) {
    context();
    const SceneConfig scene = moon_scene();
    ChannelConfig ch = test::straight_channel(30, 30, 96, 20, 64);
    ch.orientation = {0.0, 10.0, 0.0};  // from 10 degrees under the horizon to 30 above it
    const ClusterConfig cluster = one_channel(ch);
    SceneRenderer r(cluster, ch, scene);
    const Image up = r.render(moon_night(kSunDown, kMoonUp));
    const Image set = r.render(moon_night(kSunDown, -kMoonUp));  // 40 degrees under the horizon
    const Image sun_there = r.render(moon_night(kMoonUp, -kMoonUp));
    // The ratio the renderer should use: the Moon's V at its phase angle, seen from the camera.
    const glm::dvec3 moon_m = moon_night(kSunDown, kMoonUp).bodies[2].position_m;
    const double alpha =
        glm::degrees(std::acos(glm::dot(glm::normalize(kAu * kSunDown - moon_m),
                                        glm::normalize(moon_night(kSunDown, kMoonUp).camera_position_m - moon_m))));
    const double expected = std::pow(10.0, -0.4 * (moon_v(alpha, kMoonDistance) - kSunMagnitudeV));
    // Per colour channel, the least-squares scale of the Sun's frame that gives the Moon's part,
    // and the largest pixel left over.
    for (int c = 0; c < 3; ++c) {
        double xy = 0.0, xx = 0.0, peak = 0.0, worst = 0.0;
        for (size_t i = static_cast<size_t>(c); i < up.rgba.size(); i += 4) {
            const double part = up.rgba[i] - set.rgba[i], sun = sun_there.rgba[i] - set.rgba[i];
            xy += part * sun;
            xx += sun * sun;
            peak = std::max(peak, part);
        }
        const double scale = xy / xx;
        for (size_t i = static_cast<size_t>(c); i < up.rgba.size(); i += 4)
            worst = std::max(worst, std::abs(up.rgba[i] - set.rgba[i] - scale * (sun_there.rgba[i] - set.rgba[i])));
        std::printf(
            "channel %d: the Moon's part peaks at %.3g, %.4g x the Sun's frame (phase curve: %.4g at %.1f deg), "
            "worst pixel off by %.2g of the peak\n",
            c, peak, scale, expected, alpha, worst / peak);
        EXPECT_GT(peak, 0.0);
        EXPECT_NEAR(scale, expected, 0.02 * expected) << "channel " << c;
        EXPECT_LT(worst, 0.01 * peak) << "channel " << c;
    }
    test::maybe_write_frame("moonlit-sky", up);
}

TEST(MoonlitSky, TwoHalfChannelsEqualOneWideChannel) {
    context();
    const SceneConfig scene = moon_scene();
    ChannelConfig left = test::straight_channel(30, 0, 64, 20, 64), right = test::straight_channel(0, 30, 64, 20, 64),
                  wide = test::straight_channel(30, 30, 128, 20, 64);
    for (ChannelConfig* ch : {&left, &right, &wide}) ch->orientation = {60.0, 10.0, 0.0};  // toward the Moon's side
    ClusterConfig cluster;
    cluster.channels = {left, right, wide};
    SceneRenderer l(cluster, left, scene), r(cluster, right, scene), w(cluster, wide, scene);
    const Snapshot s = moon_night(kSunDown, kMoonUp);
    const test::SeamDifference d = test::seam_difference(l.render(s), r.render(s), w.render(s));
    std::printf("moonlit sky: seam difference %.3g of the peak %.3g\n", d.worst / d.peak, d.peak);
    EXPECT_GT(d.peak, 0.0);
    EXPECT_LT(d.worst, 1e-4 * d.peak);
}

TEST(MoonlitSky, TheMastersExposureSeesTheMoonsSky) {
    const ClusterConfig cluster = load_cluster_config(test::source_path("configs/planets-tonight-dome.json"));
    const SceneConfig scene = load_scene_config(cluster.scene_file);
    const ShowScript show = ShowScript::load(cluster.show_file, scene);
    const Snapshot night = make_frame_snapshot(cluster, scene, show, 0);
    const uint16_t earth = scene.find("earth")->id, moon = scene.find("moon")->id, sun = scene.find("sun")->id;
    const glm::dvec3 centre = night.bodies[earth].position_m;
    // The Moon mirrored through the Earth's centre (set, as far away), and the Sun moved there too
    // for a day with the Moon up.
    auto mirrored = [&](const glm::dvec3& p) { return 2.0 * centre - p; };
    Snapshot moon_set = night, day = night, day_moon_set = night;
    moon_set.bodies[moon].position_m = mirrored(night.bodies[moon].position_m);
    day.bodies[sun].position_m = mirrored(night.bodies[sun].position_m);
    day_moon_set = day;
    day_moon_set.bodies[moon].position_m = moon_set.bodies[moon].position_m;
    const AutoExposure exposure(cluster, scene);
    const double lit = exposure.metered_luminance(night), dark = exposure.metered_luminance(moon_set);
    const double day_lit = exposure.metered_luminance(day), day_dark = exposure.metered_luminance(day_moon_set);
    std::printf("metered luminance: Moon up %.3g, set %.3g (exposure %.3g, %.3g); by day %.6g, %.6g\n", lit, dark,
                exposure.exposure(night), exposure.exposure(moon_set), day_lit, day_dark);
    EXPECT_GT(lit, 10.0 * dark);
    EXPECT_LT(exposure.exposure(night), 0.5 * exposure.exposure(moon_set));
    EXPECT_GT(day_lit, 1e3 * lit);
    EXPECT_EQ(day_lit, day_dark) << "by day the Moon's light is not added";
}

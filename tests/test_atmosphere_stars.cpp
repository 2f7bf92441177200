// Stars through the atmosphere, in physical units (the Sun at 2e9 cd/m^2, a V = 0 star
// at 2.54e-6 lux) with the master's cluster-wide auto exposure: drowned by the daytime sky,
// visible at night, and visible -- dimmed by the transmittance -- through the thin rim seen from
// orbit. Real EGL renders; "visible" is judged on the 8-bit display values the PNG would hold.
// With a sky-view atmosphere each star shows only as far as the eye could see it against the sky
// behind it (shaders/shared/star_visibility.glsl): the threshold against Schaefer's relation on
// the CPU, then every star's light in the renders against the CPU's judgement, by day, in twilight
// and at night, and a fading star on the edge between two channels.
// The night sky's own glow (airglow and light pollution, a Bortle class) lights the sky and
// sets the limiting magnitude: the faintest star drawn against Schaefer's relation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "atmosphere/auto_exposure.hpp"
#include "atmosphere/production_model.hpp"
#include "atmosphere/scene_atmospheres.hpp"
#include "atmosphere/solar_scale.hpp"
#include "glare/glare_sources.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "image/frame_image.hpp"
#include "passes/star_sky.hpp"
#include "passes/star_sky_weights.hpp"
#include "scene/night_sky.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {
constexpr double kR = 6.371e6, kAu = 1.496e11;

EglContext& context() { return test::headless_gl("AtmosphereStars"); }

glm::dvec3 radec_to_vec(double ra, double dec) {
    return {std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra), std::sin(dec)};
}

// Physical scene; stars at the given world directions, of V = 1 unless `vmag` gives each one's.
// model: the atmosphere's quality level, "" for none.
// glare: with the scene's sun glare (its defaults); moon: a third body, an airless Moon.
SceneConfig make_scene(const std::string& tag, const std::string& model, const std::vector<glm::dvec3>& stars,
                       const std::vector<double>& vmag = {}, bool glare = false, bool moon = false) {
    const std::string dir = test::scratch_dir("AtmosphereStars_" + tag);
    std::string csv = "ra_deg,dec_deg,vmag,bv,name\n";
    for (size_t i = 0; i < stars.size(); ++i) {
        const glm::dvec3 v = glm::normalize(stars[i]);
        char line[160];
        double ra = glm::degrees(std::atan2(v.y, v.x));
        if (ra < 0.0) ra += 360.0;
        std::snprintf(line, sizeof line, "%.9f,%.9f,%.6f,0.6,S%zu\n", ra, glm::degrees(std::asin(v.z)),
                      vmag.empty() ? 1.0 : vmag[i], i);
        csv += line;
    }
    test::write_text(dir + "/stars.csv", csv);
    const std::string atm =
        model.empty() ? "" : R"(, "atmosphere": { "preset": "earth", "model": ")" + model + R"(" })";
    test::write_text(dir + "/scene.json", R"({ "bodies": [
        { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 2.0e9, "limb_darkening_u": 0.6 },
        { "name": "earth", "kind": "planet", "ephemeris": "earth", "radius_m": 6.371e6, "albedo": 0.3)" +
                                              atm + R"( })" +
                                              std::string(moon ? R"(,
        { "name": "moon", "kind": "moon", "ephemeris": "moon", "radius_m": 1.7374e6, "albedo": 0.12 })"
                                                               : "") +
                                              R"( ],
      "stars": { "catalog": "stars.csv", "magnitude_limit": 6.5, "psf_sigma_arcmin": 2.0, "zero_mag_flux": 2.54e-6 })" +
                                              std::string(glare ? R"(, "glare": { "strength": 1.0 })" : "") + " }");
    return load_scene_config(dir + "/scene.json");
}

ClusterConfig make_cluster(const EulerDeg& orientation, const FovDeg& fov) {
    ClusterConfig c;
    ChannelConfig ch;
    ch.name = "test";
    ch.width = ch.height = 96;
    ch.orientation = orientation;
    ch.fov = fov;
    c.channels.push_back(ch);
    c.output.auto_exposure.enabled = true;
    c.output.auto_exposure.max_exposure = 1e3;
    return c;
}

// Camera at altitude above the Earth's +Z point; camera frame (right-handed): +X = world -Y,
// +Y = world +Z (up), -Z = world +X (forward).
Snapshot snapshot(double altitude_m, const glm::dvec3& sun_dir) {
    Snapshot s;
    s.bodies.resize(2);
    s.bodies[0].id = 0;
    s.bodies[1].id = 1;
    s.bodies[0].position_m = kAu * glm::normalize(sun_dir);
    s.camera_position_m = glm::dvec3(0.0, 0.0, kR + altitude_m);
    s.camera_orientation = glm::quat_cast(glm::dmat3(glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1), glm::dvec3(-1, 0, 0)));
    return s;
}

struct Pair {
    Image with, without;
    double exposure;
};

// Renders the snapshot with and without stars at the cluster's auto exposure.
Pair render_pair(const ClusterConfig& cluster, const SceneConfig& scene, Snapshot s) {
    context();
    SceneRenderer r(cluster, cluster.channels[0], scene);
    const AutoExposure ae(cluster, scene);
    Pair p;
    p.exposure = ae.exposure(s);
    s.settings.exposure = static_cast<float>(p.exposure);
    s.settings.star_magnitude_limit = 6.5f;
    p.with = r.render(s);
    s.settings.star_magnitude_limit = -30.0f;  // no star is that bright: the same frame without stars
    p.without = r.render(s);
    return p;
}

// Largest difference between the two frames in 8-bit display levels (exposure, clamp, sRGB).
double max_display_difference(const Pair& p) {
    double m = 0.0;
    for (size_t i = 0; i < p.with.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        const double a = linear_to_srgb(static_cast<float>(p.with.rgba[i] * p.exposure));
        const double b = linear_to_srgb(static_cast<float>(p.without.rgba[i] * p.exposure));
        m = std::max(m, 255.0 * std::fabs(a - b));
    }
    return m;
}

double luminance(const float* px) { return 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2]; }
}  // namespace

TEST(AtmosphereStars, DrownedAtNoonVisibleAtNight) {
    // Stars around the zenith; the channel looks straight up.
    std::vector<glm::dvec3> stars;
    for (int i = 0; i < 12; ++i) stars.push_back(radec_to_vec(glm::radians(30.0 * i), glm::radians(80.0)));
    const SceneConfig scene = make_scene("ground", "low", stars);
    const ClusterConfig cluster = make_cluster({0.0, 90.0, 0.0}, {30.0, 30.0, 30.0, 30.0});
    const auto sun_at = [](double zenith_deg) {
        const double z = glm::radians(zenith_deg);
        return glm::dvec3(std::sin(z), 0.0, std::cos(z));
    };
    const Pair noon = render_pair(cluster, scene, snapshot(2.0, sun_at(30.0)));
    const Pair night = render_pair(cluster, scene, snapshot(2.0, sun_at(120.0)));
    std::printf("noon: exposure %.3g, stars change the display by %.3f levels; night: exposure %.3g, %.1f levels\n",
                noon.exposure, max_display_difference(noon), night.exposure, max_display_difference(night));
    EXPECT_LT(max_display_difference(noon), 0.5);    // invisible: not even one 8-bit step
    EXPECT_GT(max_display_difference(night), 50.0);  // plainly visible
    EXPECT_GT(night.exposure, 1e4 * noon.exposure);
}

TEST(AtmosphereStars, SeenThroughTheThinRimFromOrbitDimmedByTheTransmittance) {
    // From 400 km, on the night side (the Sun behind the Earth), looking at the limb along +X.
    const double h = 400e3, d = kR + h;
    const double dip = std::acos(kR / d);  // the ground horizon lies this far below the horizontal
    // Stars behind the rim: rays whose closest approach to the centre lies 5..50 km above the ground.
    std::vector<glm::dvec3> stars;
    std::vector<double> tangent_km;
    for (double tk : {5.0, 10.0, 20.0, 30.0, 50.0})
        for (double az : {-6.0, 0.0, 6.0}) {
            const double a = std::asin((kR + tk * 1e3) / d);  // angle from the nadir
            const double elev = -(glm::half_pi<double>() - a);
            const double y = glm::radians(az);
            stars.push_back(glm::dvec3(std::cos(elev) * std::cos(y), -std::cos(elev) * std::sin(y), std::sin(elev)));
            tangent_km.push_back(tk);
        }
    const ClusterConfig cluster = make_cluster({0.0, -glm::degrees(dip), 0.0}, {10.0, 10.0, 6.0, 6.0});
    const Snapshot s = snapshot(h, glm::dvec3(-1.0, 0.0, -0.2));
    const Pair air = render_pair(cluster, make_scene("rim_air", "low", stars), s);
    ClusterConfig fixed = cluster;  // the vacuum render at the same exposure
    const Pair vacuum = [&] {
        context();
        SceneRenderer r(fixed, fixed.channels[0], make_scene("rim_vacuum", "", stars));
        Snapshot v = s;
        v.settings.exposure = static_cast<float>(air.exposure);
        Pair p;
        p.exposure = air.exposure;
        v.settings.star_magnitude_limit = 6.5f;
        p.with = r.render(v);
        v.settings.star_magnitude_limit = -30.0f;
        p.without = r.render(v);
        return p;
    }();
    // Star light (with minus without) summed over the frame, through air and through vacuum.
    double through_air = 0.0, in_vacuum = 0.0;
    for (int i = 0; i < air.with.width * air.with.height; ++i) {
        through_air += luminance(&air.with.rgba[4 * i]) - luminance(&air.without.rgba[4 * i]);
        in_vacuum += luminance(&vacuum.with.rgba[4 * i]) - luminance(&vacuum.without.rgba[4 * i]);
    }
    std::printf("rim: star light through the air %.4g, in vacuum %.4g (ratio %.3f), display difference %.1f levels\n",
                through_air, in_vacuum, through_air / in_vacuum, max_display_difference(air));
    ASSERT_GT(in_vacuum, 0.0);
    EXPECT_LT(through_air, 0.9 * in_vacuum);       // dimmed: the rays cross tens of km of air
    EXPECT_GT(through_air, 0.05 * in_vacuum);      // but not hidden: the rim is thin
    EXPECT_GT(max_display_difference(air), 20.0);  // and visible on the display
}

namespace {
namespace at = cupola::atmosphere;
namespace sh = cupola::shading;

// Schaefer 1990's threshold as the paper writes it: the star's illuminance in foot-candles, the
// background in nanolamberts (log B < 3.17: the rods' constants).
double schaefer_limit(double background_cd_m2) {
    const double b_nl = background_cd_m2 * std::numbers::pi * 1e5;
    const bool rods = b_nl <= 0.0 || std::log10(b_nl) < 3.17;
    const double c1 = std::pow(10.0, rods ? -9.8 : -8.35);
    const double c2 = std::pow(10.0, rods ? -1.9 : -5.9);
    const double i_fc = c1 * std::pow(1.0 + std::sqrt(c2 * b_nl), 2.0);
    return -16.57 - 2.5 * std::log10(i_fc);
}

// A sky of m V-magnitudes per square arcsecond as a luminance: a V = 0 star's 2.54e-6 lux
// spread over one square arcsecond.
double sky_cd_m2(double mag_per_arcsec2) {
    const double arcsec2_sr = std::pow(std::numbers::pi / (180.0 * 3600.0), 2.0);
    return 2.54e-6 / arcsec2_sr * std::pow(10.0, -0.4 * mag_per_arcsec2);
}
}  // namespace

TEST(StarVisibility, TheEyesThresholdIsSchaefersRelation) {
    double previous = 100.0;
    for (double lg = -7.0; lg <= 5.0; lg += 0.05) {
        const double b = std::pow(10.0, lg);
        const double m = sh::eye_limiting_magnitude(static_cast<float>(b));
        EXPECT_NEAR(m, schaefer_limit(b), 2e-3) << "background " << b << " cd/m^2";
        EXPECT_LE(m, previous + 1e-4) << "a brighter sky never shows fainter stars (" << b << " cd/m^2)";
        previous = m;
    }
    EXPECT_NEAR(sh::eye_limiting_magnitude(0.0f), 7.93, 1e-3);  // a black background
    // A dark site (22 mag/arcsec^2) shows stars to about 6.6; a city sky (18) to 4.0-4.5; the
    // daytime sky (a few thousand cd/m^2) only the brightest planets.
    EXPECT_NEAR(sh::eye_limiting_magnitude(static_cast<float>(sky_cd_m2(22.0))), 6.6, 0.1);
    EXPECT_NEAR(sh::eye_limiting_magnitude(static_cast<float>(sky_cd_m2(18.0))), 4.25, 0.25);
    const double day = sh::eye_limiting_magnitude(5000.0f);
    EXPECT_LT(day, -3.5);
    EXPECT_GT(day, -4.5);
}

TEST(StarVisibility, AStarFadesInAboveTheThresholdDimmedByTheAirInFront) {
    const float b = 1.0f;  // cd/m^2 behind the star; the table's value times to_cd_m2 = 1
    const float limit = sh::eye_limiting_magnitude(b);
    EXPECT_EQ(sh::star_sky_weight(sh::vec2(-1.0f, 1.0f), 1.0f, 20.0f), 1.0f);  // the ray misses the air
    EXPECT_EQ(sh::star_sky_weight(sh::vec2(b, 0.0f), 1.0f, -20.0f), 0.0f);     // behind the ground
    EXPECT_NEAR(sh::star_sky_weight(sh::vec2(b, 1.0f), 1.0f, limit), 0.0f, 1e-4);
    EXPECT_NEAR(sh::star_sky_weight(sh::vec2(b, 1.0f), 1.0f, limit - 0.25f), 0.5f, 1e-3);
    EXPECT_NEAR(sh::star_sky_weight(sh::vec2(b, 1.0f), 1.0f, limit - 0.5f), 1.0f, 1e-4);
    // Transmittance 0.1 is 2.5 magnitudes of extinction.
    EXPECT_NEAR(sh::star_sky_weight(sh::vec2(b, 0.1f), 1.0f, limit - 2.75f), 0.5f, 1e-3);
    // The table's value is scaled into cd/m^2: ten times the scale, a brighter sky, a lower limit.
    EXPECT_LT(sh::star_sky_weight(sh::vec2(b, 1.0f), 10.0f, limit - 0.25f), 0.01f);
}

namespace {
glm::dvec3 sun_at_zenith_deg(double zenith_deg) {
    const double z = glm::radians(zenith_deg);
    return glm::dvec3(std::sin(z), 0.0, std::cos(z));
}

// The CPU's judgement of a star, with the shared code and the table the GPU renders for the same
// camera distance and Sun.
struct SkyJudge {
    at::ProductionAtmosphere model;
    float d_m;
    sh::vec3 c_hat, sun;
    float to_cd_m2;

    SkyJudge(const SceneConfig& scene, const Snapshot& s)
        : model(scene.bodies[1].atmosphere.parameters, at::production_quality(scene.bodies[1].atmosphere.model)),
          d_m(static_cast<float>(glm::length(s.camera_position_m - s.bodies[1].position_m))),
          c_hat(glm::normalize(s.bodies[1].position_m - s.camera_position_m)),
          sun(glm::normalize(s.bodies[0].position_m - s.bodies[1].position_m)),
          to_cd_m2(static_cast<float>(
              at::solar_scale(model, scene.bodies[0], glm::length(s.bodies[0].position_m - s.bodies[1].position_m)) *
              atmosphere::kPhysicalSunRadiance_cd_m2 / scene.bodies[0].radiance)) {}

    sh::vec2 behind(const glm::dvec3& dir) const {
        const at::SkyViewTable& t = model.sky_view_table(d_m, at::sky_view_table_sun_mu(-glm::dot(sun, c_hat)));
        return sh::star_sky_behind(model.shader_params(), sh::sampler2D{&t.parts[0]}, sh::sampler2D{&t.parts[1]},
                                   sh::sampler2D{&t.parts[2]}, t.size(), d_m, sh::vec3(dir), c_hat, sun);
    }
    double weight(const glm::dvec3& dir, double vmag) const {
        return sh::star_sky_weight(behind(dir), to_cd_m2, static_cast<float>(vmag));
    }
};

// The star light of a frame: (with - without) luminance times each pixel's solid angle, summed:
// a star's flux when its whole PSF is in the frame.
double star_light(const Image& with, const Image& without, const ChannelFrustum& f) {
    const double sx = (f.tan_left() + f.tan_right()) / with.width, sy = (f.tan_down() + f.tan_up()) / with.height;
    double sum = 0.0;
    for (int y = 0; y < with.height; ++y)
        for (int x = 0; x < with.width; ++x) {
            const double cx = -f.tan_left() + (x + 0.5) * sx, cy = -f.tan_down() + (y + 0.5) * sy;
            const double q = 1.0 + cx * cx + cy * cy;
            sum += (luminance(with.pixel(x, y)) - luminance(without.pixel(x, y))) * sx * sy / (q * std::sqrt(q));
        }
    return sum;
}

// Each star's light alone, stars in ascending magnitude: frames with the snapshot's magnitude
// limit just past each star in turn, differenced.
std::vector<double> each_star_light(SceneRenderer& r, const ChannelFrustum& f, Snapshot s,
                                    const std::vector<double>& vmag) {
    s.settings.exposure = 1e3f;  // high enough that no star falls under the exposure's criterion
    s.settings.star_magnitude_limit = -30.0f;
    Image before = r.render(s);
    std::vector<double> out;
    for (double m : vmag) {
        s.settings.star_magnitude_limit = static_cast<float>(m + 0.01);
        Image after = r.render(s);
        out.push_back(star_light(after, before, f));
        before = std::move(after);
    }
    return out;
}

double vacuum_flux(const SceneConfig& scene, double vmag) {
    return scene.stars.zero_mag_flux * std::pow(10.0, -0.4 * vmag);
}
}  // namespace

TEST(AtmosphereStars, OnlyTheStarsTheEyeCouldSeeAgainstTheSkyAreDrawn) {
    // Eight stars of V = -1 .. 6 on a ring 15 degrees from the zenith; the channel looks up.
    std::vector<glm::dvec3> stars;
    std::vector<double> vmag;
    for (int i = 0; i < 8; ++i) {
        stars.push_back(radec_to_vec(glm::radians(45.0 * i), glm::radians(75.0)));
        vmag.push_back(i - 1.0);
    }
    const SceneConfig scene = make_scene("sky_view", "sky-view", stars, vmag);
    const ClusterConfig cluster = make_cluster({0.0, 90.0, 0.0}, {30.0, 30.0, 30.0, 30.0});
    const ChannelFrustum f = cluster.channels[0].frustum();
    context();
    SceneRenderer r(cluster, cluster.channels[0], scene);
    int twilight_split = 0;
    for (double zenith : {40.0, 96.0, 98.0, 100.0, 102.0, 120.0}) {
        const Snapshot s = snapshot(2.0, sun_at_zenith_deg(zenith));
        const SkyJudge judge(scene, s);
        const std::vector<double> light = each_star_light(r, f, s, vmag);
        int seen = 0;
        for (size_t i = 0; i < stars.size(); ++i) {
            const double w = judge.weight(stars[i], vmag[i]);
            const double ratio = light[i] / (vacuum_flux(scene, vmag[i]) * judge.behind(stars[i]).y);
            std::printf("sun at %.0f deg: V = %+.0f, limit %.2f, weight %.2f, drawn %.3f of its light\n", zenith,
                        vmag[i], sh::eye_limiting_magnitude(judge.behind(stars[i]).x * judge.to_cd_m2), w, ratio);
            EXPECT_NEAR(ratio, w, 0.1) << "sun at " << zenith << " deg, V = " << vmag[i];
            seen += w > 0.0 ? 1 : 0;
        }
        if (zenith == 40.0) {
            EXPECT_EQ(seen, 0) << "by day no star is seen";
        }
        if (zenith == 120.0) {
            EXPECT_EQ(seen, 8) << "at night every star is seen";
        }
        if (seen > 0 && seen < 8) ++twilight_split;
    }
    EXPECT_GE(twilight_split, 2) << "in twilight the sky hides the faint stars and shows the bright ones";
}

namespace {
// The snapshot with the scene's Moon (body 2) at its mean distance along moon_dir from the camera.
Snapshot with_moon(Snapshot s, const glm::dvec3& moon_dir) {
    s.bodies.resize(3);
    s.bodies[2].id = 2;
    s.bodies[2].position_m = s.camera_position_m + 3.844e8 * glm::normalize(moon_dir);
    return s;
}
}  // namespace

TEST(AtmosphereStars, AMoonUpHidesTheFaintStarsItsSkyOutshines) {
    // Six stars of V = 1 .. 6 around the zenith at night (the Sun 30 degrees down); a nearly full
    // Moon 40 degrees up behind the channel, then set 50 degrees under the horizon.
    std::vector<glm::dvec3> stars;
    std::vector<double> vmag;
    for (int i = 0; i < 6; ++i) {
        stars.push_back(radec_to_vec(glm::radians(60.0 * i), glm::radians(75.0)));
        vmag.push_back(i + 1.0);
    }
    const SceneConfig scene = make_scene("moonlit", "sky-view", stars, vmag, false, true);
    const ClusterConfig cluster = make_cluster({0.0, 90.0, 0.0}, {30.0, 30.0, 30.0, 30.0});
    const ChannelFrustum f = cluster.channels[0].frustum();
    context();
    SceneRenderer r(cluster, cluster.channels[0], scene);
    const Snapshot night = snapshot(2.0, sun_at_zenith_deg(120.0));
    int seen[2] = {0, 0};
    for (const bool up : {false, true}) {
        const Snapshot s = with_moon(night, up ? glm::dvec3(-0.766, 0.0, 0.643) : glm::dvec3(-0.643, 0.0, -0.766));
        const std::vector<double> light = each_star_light(r, f, s, vmag);
        const SkyJudge judge(scene, s);  // the Sun's sky alone: the Moon's is not in it
        for (size_t i = 0; i < stars.size(); ++i) {
            const double drawn = light[i] / (vacuum_flux(scene, vmag[i]) * judge.behind(stars[i]).y);
            std::printf("Moon %s: V = %.0f drawn %.3f of its light\n", up ? "up" : "set", vmag[i], drawn);
            seen[up ? 1 : 0] += drawn > 0.5 ? 1 : 0;
        }
    }
    EXPECT_EQ(seen[0], 6) << "under a dark sky every star";
    EXPECT_GE(seen[1], 2) << "the bright stars through the moonlit sky";
    EXPECT_LE(seen[1], 4) << "not the faint ones";
}

TEST(AtmosphereStars, AStarFadingOnTheEdgeBetweenTwoChannelsShowsAlikeInBoth) {
    // The star at the zenith, on the edge between two channels that look up side by side; its
    // magnitude puts it half-way into its fade in twilight.
    const glm::dvec3 zenith(0.0, 0.0, 1.0);
    const Snapshot s = snapshot(2.0, sun_at_zenith_deg(98.0));
    const SkyJudge judge(make_scene("edge_probe", "sky-view", {zenith}), s);
    const sh::vec2 behind = judge.behind(zenith);
    const double vmag = sh::eye_limiting_magnitude(behind.x * judge.to_cd_m2) - 0.25 + 2.5 * std::log10(behind.y);
    const SceneConfig scene = make_scene("edge", "sky-view", {zenith}, {vmag});
    const double w = judge.weight(zenith, vmag);
    ASSERT_GT(w, 0.3);
    ASSERT_LT(w, 0.7);
    ClusterConfig cluster = make_cluster({0.0, 90.0, 0.0}, {30.0, 0.0, 30.0, 30.0});
    cluster.channels.push_back(cluster.channels[0]);
    cluster.channels[1].name = "right";
    cluster.channels[1].fov = {0.0, 30.0, 30.0, 30.0};
    context();
    double halves[2];
    for (int c = 0; c < 2; ++c) {
        SceneRenderer r(cluster, cluster.channels[static_cast<size_t>(c)], scene);
        halves[c] = each_star_light(r, cluster.channels[static_cast<size_t>(c)].frustum(), s, {vmag})[0];
    }
    const double full = vacuum_flux(scene, vmag) * behind.y;
    std::printf("edge: V = %.2f, weight %.3f; left %.3f, right %.3f of its light\n", vmag, w, halves[0] / full,
                halves[1] / full);
    EXPECT_NEAR((halves[0] + halves[1]) / full, w, 0.08);  // each channel faded it alike
    EXPECT_GT(halves[0], 0.3 * w * full);                  // and it straddles the edge
    EXPECT_GT(halves[1], 0.3 * w * full);
}

// A twinkling star (shaders/shared/star_twinkle.glsl) on the edge between two channels twinkles
// alike in both, frame after frame: each channel's half is the steady half times one factor, whose
// logarithm is linear in the noise the CPU computes from the star's index and the clock alone.
// Switched off, the frames are the steady frames, bit for bit, whatever the clock.
TEST(AtmosphereStars, ATwinklingStarOnTheEdgeBetweenTwoChannelsTwinklesAlikeInBoth) {
    const glm::dvec3 zenith(0.0, 0.0, 1.0);
    const SceneConfig scene = make_scene("twinkle_edge", "sky-view", {zenith});
    ClusterConfig cluster = make_cluster({0.0, 90.0, 0.0}, {30.0, 0.0, 30.0, 30.0});
    cluster.channels.push_back(cluster.channels[0]);
    cluster.channels[1].name = "right";
    cluster.channels[1].fov = {0.0, 30.0, 30.0, 30.0};
    Snapshot s = snapshot(2.0, sun_at_zenith_deg(130.0));  // night
    const std::vector<float> clocks{0.0f, 0.04f, 0.09f, 0.17f, 0.26f, 0.43f, 0.71f, 1.3f};
    context();
    std::vector<double> factor[2];
    for (int c = 0; c < 2; ++c) {
        const ChannelConfig& ch = cluster.channels[static_cast<size_t>(c)];
        SceneRenderer r(cluster, ch, scene);
        s.settings.flags = with_twinkle_mode(0, TwinkleMode::Off);
        const double steady = each_star_light(r, ch.frustum(), s, {1.0})[0];
        ASSERT_GT(steady, 0.0);
        s.settings.flags = with_twinkle_mode(0, TwinkleMode::On);
        for (float t : clocks) {
            s.settings.twinkle_time_s = t;
            factor[c].push_back(each_star_light(r, ch.frustum(), s, {1.0})[0] / steady);
        }
        // Off: bit-identical frames at two clocks.
        s.settings.flags = with_twinkle_mode(0, TwinkleMode::Off);
        s.settings.exposure = 1e3f;
        s.settings.twinkle_time_s = 0.0f;
        const Image a = r.render(s);
        s.settings.twinkle_time_s = 0.71f;
        EXPECT_EQ(a.rgba, r.render(s).rgba) << ch.name;
    }
    double lo = 1e9, hi = 0.0, sn = 0.0, sf = 0.0, snn = 0.0, snf = 0.0, sff = 0.0;
    for (size_t k = 0; k < clocks.size(); ++k) {
        EXPECT_NEAR(factor[0][k], factor[1][k], 0.01 * factor[0][k]) << "clock " << clocks[k];
        lo = std::min(lo, factor[0][k]);
        hi = std::max(hi, factor[0][k]);
        const double n = sh::twinkle_noise(0u, clocks[k]), f = std::log(factor[0][k]);
        sn += n, sf += f, snn += n * n, snf += n * f, sff += f * f;
    }
    const double m = static_cast<double>(clocks.size());
    const double corr = (snf - sn * sf / m) / std::sqrt((snn - sn * sn / m) * (sff - sf * sf / m));
    const double slope = (snf - sn * sf / m) / (snn - sn * sn / m);
    std::printf("twinkle on the edge: factors %.3f .. %.3f, log-factor vs noise: correlation %.5f, slope %.3f\n", lo,
                hi, corr, slope);
    EXPECT_GT(hi / lo, 1.2);
    EXPECT_GT(corr, 0.999);
    // The slope is sqrt(ln(1 + sigma^2)) for the zenith's sigma 2 m above the ground (about 0.27).
    EXPECT_NEAR(slope, std::sqrt(std::log(1.0 + 0.27 * 0.27)), 0.03);
}

TEST(AtmosphereStars, StarWeightsAreRenderedOnlyWhenTheirInputsChange) {
    std::vector<glm::dvec3> stars;
    for (int i = 0; i < 4; ++i) stars.push_back(radec_to_vec(glm::radians(90.0 * i), glm::radians(70.0)));
    const SceneConfig scene = make_scene("weights_keyed", "sky-view", stars, {0.0, 1.0, 2.0, 3.0});
    const ClusterConfig cluster = make_cluster({0.0, 90.0, 0.0}, {30.0, 30.0, 30.0, 30.0});
    context();
    SceneRenderer r(cluster, cluster.channels[0], scene);
    Snapshot s = snapshot(2.0, sun_at_zenith_deg(98.0));
    s.settings.exposure = 1e3f;
    s.settings.star_magnitude_limit = 6.5f;
    for (int i = 0; i < 3; ++i) r.render(s);
    EXPECT_EQ(r.star_weight_renders(), 1) << "the same snapshot three times: one render";
    s.settings.exposure = 1.1e3f;  // the same stars left by the exposure: the weights stand
    r.render(s);
    EXPECT_EQ(r.star_weight_renders(), 1);
    s.bodies[0].position_m = kAu * sun_at_zenith_deg(99.0);
    r.render(s);
    EXPECT_EQ(r.star_weight_renders(), 2) << "the Sun moved a degree";
    s.settings.star_magnitude_limit = 1.5f;  // two stars fewer to judge
    r.render(s);
    EXPECT_EQ(r.star_weight_renders(), 3);
    // The directions' grid: a millionth of a radian does not move a direction off its grid point.
    const glm::vec3 v = glm::normalize(glm::vec3(0.6f, 0.8f, 0.0f));
    const glm::vec3 g = StarSkyWeights::on_grid(v);
    EXPECT_EQ(StarSkyWeights::on_grid(glm::normalize(v + glm::vec3(2e-6f, -1e-6f, 1e-6f))), g);
    EXPECT_LT(glm::length(g - v), 1e-4f);
}

TEST(AtmosphereStars, TheMasterGivesAStarHiddenByTheSkyNoGlare) {
    // A V = -1 star (a glare source) 15 degrees from the zenith: the master's sources by day, in
    // twilight and at night, against the judgement of the slaves' star pass.
    const glm::dvec3 star = radec_to_vec(0.0, glm::radians(75.0));
    const SceneConfig scene = make_scene("glare_sources", "sky-view", {star}, {-1.0}, true);
    const SceneAtmospheres atmospheres(scene);
    const GlareSources sources(scene, &atmospheres);
    int shown = 0;
    for (double zenith : {40.0, 86.0, 88.0, 89.0, 90.0, 91.0, 92.0, 120.0}) {
        Snapshot s = snapshot(2.0, sun_at_zenith_deg(zenith));
        s.settings.exposure = 1e6f;  // high enough that the exposure alone would give it a glare
        const SkyJudge judge(scene, s);
        const BodyState* sun_state = &s.bodies[0];
        const double master = atmospheres.star_sky_weight(s, star, -1.0, sun_state, &scene.bodies[0]);
        double glare = 0.0;
        for (const GlareSource& g : sources.select(s))
            if (g.body == GlareSource::kCatalogStar) glare += g.irradiance.y;
        std::printf("sun at %.0f deg: master's weight %.3f, the slaves' %.3f, glare irradiance %.3g\n", zenith, master,
                    judge.weight(star, -1.0), glare);
        EXPECT_NEAR(master, judge.weight(star, -1.0), 0.15) << "sun at " << zenith << " deg";
        if (master == 0.0) {
            EXPECT_EQ(glare, 0.0) << "a star the sky hides has no glare (sun at " << zenith << " deg)";
        }
        if (master == 1.0) {
            EXPECT_GT(glare, 0.0) << "sun at " << zenith << " deg";
        }
        shown += glare > 0.0 ? 1 : 0;
    }
    EXPECT_EQ(shown, 5) << "from 89 degrees on";
}

TEST(AtmosphereStars, InASolarEclipseTheMasterDoesNotJudgeStarsAgainstTheSunlitSky) {
    // By day a V = -1 star has no glare; with the Moon over the Sun (its sky has no eclipse
    // shadow on the master's side) the exposure alone decides again.
    const glm::dvec3 star = radec_to_vec(0.0, glm::radians(75.0));
    const SceneConfig scene = make_scene("glare_eclipse", "sky-view", {star}, {-1.0}, true, true);
    const SceneAtmospheres atmospheres(scene);
    const GlareSources sources(scene, &atmospheres);
    Snapshot s = snapshot(2.0, sun_at_zenith_deg(40.0));
    s.settings.exposure = 1e6f;
    s.bodies.resize(3);
    s.bodies[2].id = 2;
    const auto star_glare = [&] {
        double e = 0.0;
        for (const GlareSource& g : sources.select(s))
            if (g.body == GlareSource::kCatalogStar) e += g.irradiance.y;
        return e;
    };
    const glm::dvec3 to_sun = glm::normalize(s.bodies[0].position_m - s.camera_position_m);
    s.bodies[2].position_m = s.camera_position_m - 3.844e8 * to_sun;  // behind the camera: no eclipse
    EXPECT_EQ(star_glare(), 0.0);
    s.bodies[2].position_m = s.camera_position_m + 3.844e8 * to_sun;  // on the Sun: total
    EXPECT_GT(star_glare(), 0.0);
}

// ---- The night sky's own brightness (shaders/shared/night_sky.glsl, common/scene/night_sky) ----

namespace {
// Schaefer's (1990, equations 2 and 3) naked-eye limiting magnitude for a sky of B V
// mag/arcsec^2, written here from the paper's constants: I = C1 (1 + sqrt(C2 B))^2 foot-candles
// with B in nanolamberts (1 cd/m^2 = pi 10^5 nL), C1 = 10^-9.8 and C2 = 10^-1.9 below 10^3.17 nL
// (rods), 10^-8.35 and 10^-5.9 above (cones); a V = 0 star gives 10^-6.628 foot-candles. With the
// rods alone this is the form quoted for sky-quality meters, 7.93 - 5 log10(10^(4.316 - B/5) + 1).
double schaefer_nelm(double b_mag_arcsec2) {
    const double b_nl = 1.08e5 * std::pow(10.0, -0.4 * b_mag_arcsec2) * std::numbers::pi * 1e5;
    const bool rods = b_nl < std::pow(10.0, 3.17);
    const double c1 = std::pow(10.0, rods ? -9.8 : -8.35), c2 = std::pow(10.0, rods ? -1.9 : -5.9);
    const double fc = c1 * std::pow(1.0 + std::sqrt(c2 * b_nl), 2.0);
    return -2.5 * std::log10(fc / std::pow(10.0, -6.628));
}

// Krisciunas and Schaefer (1991), equation 2, with k = 0.2: the sky at zenith distance z over the zenith's.
double ks_gradient(double z_rad) {
    const double x = 1.0 / std::sqrt(1.0 - 0.96 * std::sin(z_rad) * std::sin(z_rad));
    return x * std::pow(10.0, -0.4 * 0.2 * (x - 1.0));
}
}  // namespace

TEST(NightSky, BortleClassesMagnitudesLuminancesAndTheGradient) {
    EXPECT_DOUBLE_EQ(bortle_zenith_mag_arcsec2(1), 22.0);
    EXPECT_DOUBLE_EQ(bortle_zenith_mag_arcsec2(4), 21.09);
    EXPECT_DOUBLE_EQ(bortle_zenith_mag_arcsec2(8), 18.0);
    for (int c = 2; c <= 9; ++c) EXPECT_LT(bortle_zenith_mag_arcsec2(c), bortle_zenith_mag_arcsec2(c - 1));
    EXPECT_THROW(bortle_zenith_mag_arcsec2(0), std::invalid_argument);
    EXPECT_THROW(bortle_zenith_mag_arcsec2(10), std::invalid_argument);
    // 22 mag/arcsec^2 is the natural night sky, about 1.7e-4 cd/m^2.
    EXPECT_NEAR(sky_brightness_cd_m2(22.0), 1.08e5 * std::pow(10.0, -8.8), 1e-3 * 1.7e-4);
    EXPECT_NEAR(sky_brightness_cd_m2(18.0) / sky_brightness_cd_m2(22.0), std::pow(10.0, 1.6), 1e-3 * 39.8);
    // The rods' branch is the sky-quality meters' form; a city sky is in the cones' branch.
    EXPECT_NEAR(schaefer_nelm(22.0), 7.93 - 5.0 * std::log10(std::pow(10.0, 4.316 - 22.0 / 5.0) + 1.0), 0.01);
    EXPECT_GT(schaefer_nelm(18.0), 7.93 - 5.0 * std::log10(std::pow(10.0, 4.316 - 18.0 / 5.0) + 1.0));
    for (double z_deg : {0.0, 30.0, 60.0, 75.0, 85.0, 90.0}) {
        const double z = glm::radians(z_deg);
        EXPECT_NEAR(sh::night_sky_gradient(static_cast<float>(std::cos(z))), ks_gradient(z), 1e-4 * ks_gradient(z))
            << z_deg;
    }
    EXPECT_GT(sh::night_sky_gradient(0.0f), 2.0f);  // the horizon glows more than twice the zenith
    EXPECT_NEAR(sh::night_sky_at_height(1.0f, 8000.0f), std::exp(-1.0), 1e-6);
}

TEST(NightSky, TheGlowLightsTheSkyItsZenithLuminanceAndBrighterTowardTheHorizon) {
    const SceneConfig scene = make_scene("glow", "sky-view", {radec_to_vec(0.0, glm::radians(-80.0))});
    const ClusterConfig cluster = make_cluster({0.0, 45.0, 0.0}, {30.0, 30.0, 50.0, 40.0});
    context();
    SceneRenderer r(cluster, cluster.channels[0], scene);
    Snapshot s = snapshot(2.0, sun_at_zenith_deg(130.0));
    s.settings.exposure = 1.0f;
    const Image dark = r.render(s);
    s.settings.night_sky_cd_m2 = static_cast<float>(sky_brightness_cd_m2(18.0));
    const Image city = r.render(s);
    // The channel looks 45 degrees up, 90 tall: its top rows (row 0 at the top) near the zenith,
    // its bottom near the horizon.
    const ChannelFrustum f = cluster.channels[0].frustum();
    const auto glow_at_row = [&](int y) {
        return luminance(city.pixel(city.width / 2, y)) - luminance(dark.pixel(dark.width / 2, y));
    };
    const auto zenith_angle_at_row = [&](int y) {
        const double t = f.tan_up() - (y + 0.5) * (f.tan_down() + f.tan_up()) / city.height;
        return glm::radians(45.0) - std::atan(t);
    };
    const double b = s.settings.night_sky_cd_m2;
    for (int y : {4, city.height / 2, city.height - 6}) {
        const double z = zenith_angle_at_row(y);
        std::printf("zenith distance %.1f deg: glow %.4g cd/m^2, model %.4g\n", glm::degrees(z), glow_at_row(y),
                    b * ks_gradient(z));
        EXPECT_NEAR(glow_at_row(y), b * ks_gradient(z), 0.03 * b * ks_gradient(z)) << "row " << y;
    }
    EXPECT_GT(glow_at_row(city.height - 6), 1.5 * glow_at_row(4));
}

TEST(NightSky, TheFaintestStarSeenFollowsSchaefersLimitUnderBortle148) {
    // Fifty stars of V = 3.0 .. 7.9 within 6 degrees of the zenith; the channel looks up.
    std::vector<glm::dvec3> stars;
    std::vector<double> vmag;
    for (int i = 0; i < 50; ++i) {
        stars.push_back(radec_to_vec(glm::radians(137.5 * i), glm::radians(89.0 - 5.0 * std::sqrt(i / 50.0))));
        vmag.push_back(3.0 + 0.1 * i);
    }
    const SceneConfig scene = make_scene("limiting_magnitude", "sky-view", stars, vmag);
    const ClusterConfig cluster = make_cluster({0.0, 90.0, 0.0}, {30.0, 30.0, 30.0, 30.0});
    const ChannelFrustum f = cluster.channels[0].frustum();
    context();
    SceneRenderer r(cluster, cluster.channels[0], scene);
    for (int bortle : {1, 4, 8}) {
        const double b_mag = bortle_zenith_mag_arcsec2(bortle);
        Snapshot s = snapshot(2.0, sun_at_zenith_deg(130.0));
        s.settings.night_sky_cd_m2 = static_cast<float>(sky_brightness_cd_m2(b_mag));
        const SkyJudge judge(scene, s);
        const std::vector<double> light = each_star_light(r, f, s, vmag);
        double faintest = -99.0, faintest_seen = -99.0;
        for (size_t i = 0; i < stars.size(); ++i) {
            const double t = judge.behind(stars[i]).y;
            if (light[i] / (vacuum_flux(scene, vmag[i]) * t) > 0.05) {
                faintest = vmag[i];
                faintest_seen = vmag[i] - 2.5 * std::log10(t);  // through the air in front
            }
        }
        std::printf(
            "Bortle %d (%.2f mag/arcsec^2): faintest star drawn V = %.1f, %.2f through the air; "
            "Schaefer's limit %.2f\n",
            bortle, b_mag, faintest, faintest_seen, schaefer_nelm(b_mag));
        EXPECT_NEAR(faintest_seen, schaefer_nelm(b_mag), 0.3) << "Bortle " << bortle;
    }
}

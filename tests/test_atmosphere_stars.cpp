// Stars through the atmosphere, in physical units (the Sun at 2e9 cd/m^2, a V = 0 star
// at 2.54e-6 lux) with the master's cluster-wide auto exposure: drowned by the daytime sky,
// visible at night, and visible -- dimmed by the transmittance -- through the thin rim seen from
// orbit. Real EGL renders; "visible" is judged on the 8-bit display values the PNG would hold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "atmosphere/auto_exposure.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "image/frame_image.hpp"
#include "scene_renderer.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {
constexpr double kR = 6.371e6, kAu = 1.496e11;

EglContext& context() { return test::headless_gl("AtmosphereStars"); }

glm::dvec3 radec_to_vec(double ra, double dec) {
    return {std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra), std::sin(dec)};
}

// Physical scene; stars (V = 1) at the given world directions.
SceneConfig make_scene(const std::string& tag, bool atmosphere, const std::vector<glm::dvec3>& stars) {
    const std::string dir = test::scratch_dir("AtmosphereStars_" + tag);
    std::string csv = "ra_deg,dec_deg,vmag,bv,name\n";
    for (size_t i = 0; i < stars.size(); ++i) {
        const glm::dvec3 v = glm::normalize(stars[i]);
        char line[160];
        double ra = glm::degrees(std::atan2(v.y, v.x));
        if (ra < 0.0) ra += 360.0;
        std::snprintf(line, sizeof line, "%.9f,%.9f,1.0,0.6,S%zu\n", ra, glm::degrees(std::asin(v.z)), i);
        csv += line;
    }
    test::write_text(dir + "/stars.csv", csv);
    const std::string atm = atmosphere ? R"(, "atmosphere": { "preset": "earth", "model": "low" })" : "";
    test::write_text(dir + "/scene.json", R"({ "bodies": [
        { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 2.0e9, "limb_darkening_u": 0.6 },
        { "name": "earth", "kind": "planet", "ephemeris": "earth", "radius_m": 6.371e6, "albedo": 0.3)" +
                                              atm + R"( } ],
      "stars": { "catalog": "stars.csv", "magnitude_limit": 6.5, "psf_sigma_arcmin": 2.0, "zero_mag_flux": 2.54e-6 } })");
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
    const SceneConfig scene = make_scene("ground", true, stars);
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
    const Pair air = render_pair(cluster, make_scene("rim_air", true, stars), s);
    ClusterConfig fixed = cluster;  // the vacuum render at the same exposure
    const Pair vacuum = [&] {
        context();
        SceneRenderer r(fixed, fixed.channels[0], make_scene("rim_vacuum", false, stars));
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

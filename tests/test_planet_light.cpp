// Planets as a planetarium shows them (passes/planet_light, passes/planet_point_pass, body.frag):
//   - the phase curves (scene/planet_magnitude, Mallama & Hilton 2018) at known points and their
//     continuation past each fit;
//   - the disc-integrated magnitude of each planet's rendered disc (real maps, real EGL) within
//     0.2 mag of the curve at five phase angles;
//   - Jupiter approached from 10 AU to 10 radii: the frame's energy follows the curve, and no
//     frame-to-frame step exceeds 2 % beyond what the distance explains, across the point-to-disc
//     handover;
//   - a point and a fading disc on the edge between two channels equal one wide channel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "atmosphere/solar_scale.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "image/frame_image.hpp"
#include "scene/planet_magnitude.hpp"
#include "scene/sky_positions.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "support/planet_frames.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

constexpr double kAu = kAstronomicalUnit_m;

struct PlanetInfo {
    const char* name;
    double radius_m, flattening;
    std::array<double, 5> phases_deg;
};
const PlanetInfo kPlanets[] = {
    {"mercury", 2.4405e6, 0.0, {10, 40, 70, 100, 130}},  {"venus", 6.0518e6, 0.0, {10, 50, 90, 130, 150}},
    {"mars", 3.39619e6, 0.00589, {5, 20, 40, 60, 90}},   {"jupiter", 7.1492e7, 0.06487, {2, 6, 10, 40, 90}},
    {"saturn", 6.0268e7, 0.09796, {2, 5, 20, 60, 100}},  {"uranus", 2.5559e7, 0.02293, {1, 2, 3, 50, 100}},
    {"neptune", 2.4764e7, 0.01708, {1, 2, 20, 60, 100}},
};

SceneConfig planet_scene(const std::string& dir, const PlanetInfo& p) {
    nlohmann::json scene = {
        {"bodies",
         {{{"name", "sun"}, {"kind", "star"}, {"ephemeris", "sun"}, {"radius_m", 6.957e8}, {"radiance", 5.8e4}},
          {{"name", p.name},
           {"kind", "planet"},
           {"ephemeris", p.name},
           {"radius_m", p.radius_m},
           {"flattening", p.flattening},
           {"texture", std::string("/usr/share/openuniverse/textures/") + p.name + ".jpg"},
           {"albedo", 0.5}}}},
        {"stars", {{"catalog", test::source_path("data/stars/bright_stars.csv")}, {"magnitude_limit", -2.0}}}};
    test::write_text(dir + "/scene.json", scene.dump());
    return load_scene_config(dir + "/scene.json");
}

ChannelConfig channel(double left_deg, double right_deg, int width, double up_down_deg = 20.0) {
    return test::straight_channel(left_deg, right_deg, width, up_down_deg);
}

// The planet at the origin, the Sun at r AU, the camera at delta_m at phase_deg from it.
Snapshot planet_view(double phase_deg, double r_au, double delta_m) {
    return test::phase_view(phase_deg, r_au * kAu, delta_m);
}

using test::frame_flux;
void maybe_write(const std::string& name, const Image& img) { test::maybe_write_frame(name, img); }

double sun_irradiance_1au(const SceneConfig& scene) {
    return atmosphere::sun_irradiance_scene_units(scene.bodies[0], kAu);
}

PlanetGeometry geometry(double phase_deg, double r_au, double delta_m) {
    PlanetGeometry g;
    g.sun_distance_au = r_au;
    g.observer_distance_au = delta_m / kAu;
    g.phase_deg = phase_deg;
    return g;
}

}  // namespace

TEST(PlanetMagnitude, CurvesAtKnownPointsAndPastTheirFits) {
    // Jupiter at a typical opposition (r 5.2, Delta 4.2 AU): -9.395 + 5 log10(21.84) = -2.70.
    EXPECT_NEAR(*planet_magnitude_v("jupiter", {5.2, 4.2, 0.0, 0.0, 0.0}), -2.699, 0.002);
    // Venus' two fits meet at 163.7 deg to 0.05 mag; Mars' at 50 deg to 0.01.
    auto v = [](const char* p, double a) { return *planet_magnitude_v(p, {1.0, 1.0, a, 0.0, 0.0}); };
    EXPECT_NEAR(v("venus", 163.69), v("venus", 163.71), 0.05);
    EXPECT_NEAR(v("mars", 49.99), v("mars", 50.01), 0.01);
    // Past Jupiter's fit (130 deg) the curve goes on as a Lambert sphere's, continuous and fainter.
    EXPECT_NEAR(v("jupiter", 130.0), v("jupiter", 130.001), 0.001);
    EXPECT_GT(v("jupiter", 170.0), v("jupiter", 130.0) + 2.0);
    EXPECT_TRUE(std::isfinite(v("neptune", 180.0)));
    EXPECT_FALSE(planet_magnitude_v("pluto", {}).has_value());
    // Saturn with its rings (equation 10) at an opposition with the rings wide open (r 9.5, Delta
    // 8.5 AU, 26.7 deg): -8.914 - (1.825 + 0.378) sin(26.7 deg) + 5 log10(80.75) = -0.369; edge-on it
    // is never fainter than the globe alone; past 6.5 deg it follows the globe's curve.
    PlanetGeometry open{9.5, 8.5, 0.0, 26.7, 26.7};
    EXPECT_NEAR(saturn_with_rings_magnitude_v(open), -0.369, 0.002);
    PlanetGeometry edge_on{9.5, 8.5, 4.0, 0.0, 0.0};
    EXPECT_EQ(saturn_with_rings_magnitude_v(edge_on), *planet_magnitude_v("saturn", edge_on));
    PlanetGeometry at_fit{9.5, 8.5, 6.5, 20.0, 20.0}, past_fit = at_fit;
    past_fit.phase_deg = 30.0;
    EXPECT_NEAR(saturn_with_rings_magnitude_v(past_fit) - saturn_with_rings_magnitude_v(at_fit),
                *planet_magnitude_v("saturn", past_fit) - *planet_magnitude_v("saturn", at_fit), 1e-9);
    // Whose point light includes its rings (the slaves' points and the master's exposure share it):
    // only a ringed Saturn's has a measured magnitude.
    EXPECT_TRUE(magnitude_includes_rings("saturn", true));
    EXPECT_FALSE(magnitude_includes_rings("saturn", false));
    EXPECT_FALSE(magnitude_includes_rings("jupiter", true));
    EXPECT_NEAR(lambert_phase(0.0), 1.0, 1e-15);
    EXPECT_NEAR(lambert_phase(glm::radians(90.0)), 1.0 / std::numbers::pi, 1e-15);
}

TEST(PlanetLight, EachPlanetsRenderedDiscIsWithinAFifthOfAMagnitudeOfItsCurve) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("planet_light_magnitudes");
    // A narrow channel, so that the disc (1.6 deg across, 170 pixels) is seen from 72 radii: the fits
    // are for distant observers, who see the whole lit hemisphere (from 5 radii the limb hides
    // much of a crescent).
    const ChannelConfig ch = channel(1, 1, 256, 1);
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    for (const PlanetInfo& p : kPlanets) {
        const SceneConfig scene = planet_scene(dir, p);
        SceneRenderer renderer(cluster, ch, scene);
        const double delta_m = p.radius_m / std::sin(glm::radians(0.8));
        for (const double a : p.phases_deg) {
            const Image img = renderer.render(planet_view(a, 5.0, delta_m));
            const double flux = frame_flux(img, ch);
            if (a == p.phases_deg[3]) maybe_write(std::string("disc-") + p.name, img);
            const double rendered_v = kSunMagnitudeV - 2.5 * std::log10(flux / sun_irradiance_1au(scene));
            const double curve_v = *planet_magnitude_v(p.name, geometry(a, 5.0, delta_m));
            EXPECT_NEAR(rendered_v, curve_v, 0.2) << p.name << " at phase " << a;
            std::printf("%-8s phase %5.1f: rendered %+.3f, curve %+.3f mag\n", p.name, a, rendered_v, curve_v);
        }
    }
}

TEST(PlanetLight, JupiterApproachedFromTenAuToTenRadiiHasNoStep) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("planet_light_approach");
    const PlanetInfo& jupiter = kPlanets[3];
    const SceneConfig scene = planet_scene(dir, jupiter);
    const ChannelConfig ch = channel(20, 20, 256);
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);
    const double far_m = 10.0 * kAu, near_m = 10.0 * jupiter.radius_m, phase = 30.0;
    const int frames = 120;
    double previous_ratio = 0.0, worst_step = 0.0, worst_level = 0.0;
    for (int i = 0; i < frames; ++i) {
        const double delta_m = far_m * std::pow(near_m / far_m, double(i) / (frames - 1));
        const Image img = renderer.render(planet_view(phase, 5.2, delta_m));
        const double measured = frame_flux(img, ch);
        for (const int shown : {70, 78, 82, 86, 90, 99})
            if (i == shown) maybe_write("approach-" + std::to_string(i), img);
        const double expected =
            sun_irradiance_1au(scene) *
            std::pow(10.0, -0.4 * (*planet_magnitude_v("jupiter", geometry(phase, 5.2, delta_m)) - kSunMagnitudeV));
        const double ratio = measured / expected;  // what the distance does not explain
        worst_level = std::max(worst_level, std::abs(ratio - 1.0));
        if (i > 0) worst_step = std::max(worst_step, std::abs(ratio / previous_ratio - 1.0));
        EXPECT_NEAR(ratio, 1.0, 0.1) << "frame " << i << ", " << delta_m / jupiter.radius_m << " radii";
        if (i > 0) {
            EXPECT_LT(std::abs(ratio / previous_ratio - 1.0), 0.02) << "frame " << i;
        }
        if (std::getenv("CUPOLA_TEST_VERBOSE"))
            std::printf("frame %3d: %8.1f radii, rho %.4f deg, ratio %.4f\n", i, delta_m / jupiter.radius_m,
                        glm::degrees(std::asin(jupiter.radius_m / delta_m)), ratio);
        previous_ratio = ratio;
    }
    std::printf("approach: worst step %.4f, worst level %.4f\n", worst_step, worst_level);
}

TEST(PlanetLight, PointAndFadingDiscAcrossAChannelEdgeEqualOneWideChannel) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("planet_light_seam");
    const PlanetInfo& jupiter = kPlanets[3];
    const SceneConfig scene = planet_scene(dir, jupiter);
    const ChannelConfig left = channel(20, 0, 128), right = channel(0, 20, 128), wide = channel(20, 20, 256);
    ClusterConfig cluster;  // the same cluster for all three: one coarsest pixel, one handover
    cluster.channels = {left, right, wide};
    SceneRenderer l(cluster, left, scene), r(cluster, right, scene), w(cluster, wide, scene);
    // As a point (0.3 AU) and half-way through the handover (disc and point both drawn).
    for (const double delta_m : {0.3 * kAu, jupiter.radius_m / std::tan(glm::radians(0.45))}) {
        const Snapshot s = planet_view(30.0, 5.2, delta_m);
        const Image a = l.render(s), b = r.render(s), c = w.render(s);
        const test::SeamDifference d = test::seam_difference(a, b, c);
        EXPECT_GT(d.peak, 0.0);
        EXPECT_LT(d.worst, 1e-4 * d.peak) << delta_m / kAu << " AU";
        EXPECT_NEAR(frame_flux(a, left) + frame_flux(b, right), frame_flux(c, wide), 1e-3 * frame_flux(c, wide));
    }
}

TEST(PlanetLight, APointOutOfViewCostsNoDraw) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("planet_light_out_of_view");
    const SceneConfig scene = planet_scene(dir, kPlanets[3]);
    const ChannelConfig ch = channel(20, 20, 256);
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);
    Snapshot s = planet_view(30.0, 5.2, 4.0 * kAu);  // a point in the middle of the channel
    const double in_view = frame_flux(renderer.render(s), ch);
    EXPECT_EQ(renderer.planet_points_drawn(), 1);
    EXPECT_GT(in_view, 0.0);
    // Turned 60 degrees away (the channel spans 20 each way): no draw, no light. (Turned the other
    // way, the Sun's point, 101 degrees from the planet, would come within its sprite's reach.)
    s.camera_orientation = s.camera_orientation * glm::angleAxis(glm::radians(-60.0), glm::dvec3(0, 1, 0));
    EXPECT_EQ(frame_flux(renderer.render(s), ch), 0.0);
    EXPECT_EQ(renderer.planet_points_drawn(), 1);
    // In view again, at an exposure that cannot show its peak (a planet by day): no draw either.
    s = planet_view(30.0, 5.2, 4.0 * kAu);
    s.settings.exposure = 1e-30f;
    renderer.render(s);
    EXPECT_EQ(renderer.planet_points_drawn(), 1);
    s.settings.exposure = 1.0f;
    renderer.render(s);
    EXPECT_EQ(renderer.planet_points_drawn(), 2);
}

namespace {

// The Sun and, if given, more bodies; no stars brighter than the limit, no corona.
SceneConfig sun_scene(const std::string& dir, const nlohmann::json& more = nlohmann::json::array()) {
    nlohmann::json bodies = {{{"name", "sun"},
                              {"kind", "star"},
                              {"ephemeris", "sun"},
                              {"radius_m", 6.957e8},
                              {"radiance", 5.8e4},
                              {"corona", 0.0}}};
    for (const auto& b : more) bodies.push_back(b);
    const nlohmann::json scene = {
        {"bodies", bodies},
        {"stars", {{"catalog", test::source_path("data/stars/bright_stars.csv")}, {"magnitude_limit", -2.0}}}};
    test::write_text(dir + "/scene.json", scene.dump());
    return load_scene_config(dir + "/scene.json");
}

// The Sun at the origin, the camera at d_m along +X (a little above the plane), looking at it.
Snapshot sun_view(double d_m) {
    Snapshot s;
    s.bodies.resize(1);
    const glm::dvec3 back = glm::normalize(glm::dvec3(1.0, 0.0, 0.02));
    s.camera_position_m = back * d_m;
    s.settings.exposure = 0.0f;
    const glm::dvec3 up(0, 0, 1), right = glm::normalize(glm::cross(up, back));
    s.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(back, right), back));
    return s;
}

}  // namespace

// The Sun from 0.1 AU (a disc 5.3 degrees across) to 100 AU (19 arcseconds, a sixth of the
// channel's 0.16-degree pixels): its light is its irradiance at the camera all the way, without a
// step and without vanishing between pixel centres (the disc alone was point-sampled).
TEST(PlanetLight, TheSunFromDiscToPointKeepsItsLight) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    EglContext gl(-1);
    const SceneConfig scene = sun_scene(test::scratch_dir("planet_light_sun"));
    const ChannelConfig ch = channel(20, 20, 256);
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);
    const double near_m = 0.1 * kAu, far_m = 100.0 * kAu;
    const int frames = 90;
    double previous = 0.0, worst_step = 0.0, worst_level = 0.0;
    for (int i = 0; i < frames; ++i) {
        const double d_m = near_m * std::pow(far_m / near_m, double(i) / (frames - 1));
        const Image img = renderer.render(sun_view(d_m));
        for (const int shown : {0, 8, 12, 16, 20, 40})
            if (i == shown) maybe_write("sun-" + std::to_string(i), img);
        const double ratio = frame_flux(img, ch) / atmosphere::sun_irradiance_scene_units(scene.bodies[0], d_m);
        worst_level = std::max(worst_level, std::abs(ratio - 1.0));
        EXPECT_NEAR(ratio, 1.0, 0.05) << "frame " << i << ", " << d_m / kAu << " AU";
        if (i > 0) {
            worst_step = std::max(worst_step, std::abs(ratio / previous - 1.0));
            EXPECT_LT(std::abs(ratio / previous - 1.0), 0.02) << "frame " << i << ", " << d_m / kAu << " AU";
        }
        previous = ratio;
    }
    std::printf("the Sun receding: worst step %.4f, worst level %.4f\n", worst_step, worst_level);
}

namespace {

// The frame's light with the Sun seen from 1 AU and the scene's dark moon (albedo 0: it adds no
// light of its own) s Sun radii from the Sun's centre.
double sun_flux_behind_a_moon(SceneRenderer& renderer, const ChannelConfig& ch, double s) {
    Snapshot snap = sun_view(kAu);
    const double alpha = std::asin(6.957e8 / kAu), moon_distance_m = 3.844e8;
    const glm::dvec3 to_sun = -glm::normalize(snap.camera_position_m);
    const glm::dvec3 to_moon = glm::angleAxis(s * alpha, glm::dvec3(0, 0, 1)) * to_sun;
    snap.bodies.resize(2);
    snap.bodies[1].id = 1;
    snap.bodies[1].position_m = snap.camera_position_m + to_moon * moon_distance_m;
    return frame_flux(renderer.render(snap), ch);
}

}  // namespace

// The Sun as a point (0.27 degrees in 0.16-degree pixels) behind a moon: the point carries the
// part of the limb-darkened disc the moon leaves (eclipse_visible_exact, the eclipse shadows' own
// function), not hidden per pixel a second time, so that in totality nothing leaks past the
// moon's edge and in a partial eclipse the light is the visible part's.
TEST(PlanetLight, TheSunsPointBehindAMoonCarriesItsDiscsVisiblePart) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("planet_light_sun_moon");
    const double a = 1.05, alpha = std::asin(6.957e8 / kAu);
    const SceneConfig config = sun_scene(dir, {{{"name", "moon"},
                                                {"kind", "moon"},
                                                {"ephemeris", "moon"},
                                                {"radius_m", std::sin(a * alpha) * 3.844e8},
                                                {"albedo", 0.0}}});
    const ChannelConfig ch = channel(20, 20, 256);
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, config);
    const double whole = atmosphere::sun_irradiance_scene_units(config.bodies[0], kAu);
    const auto u = static_cast<float>(config.bodies[0].limb_darkening_u);
    for (const double s : {0.0, 0.5, 1.0, 1.6, 3.0}) {
        const double expected = shading::eclipse_visible_exact(static_cast<float>(a), static_cast<float>(s), u);
        const double ratio = sun_flux_behind_a_moon(renderer, ch, s) / whole;
        EXPECT_NEAR(ratio, expected, 0.01) << "the moon " << s << " Sun radii from the Sun's centre";
        std::printf("moon at %.1f Sun radii: light %.4f of the Sun's, visible part %.4f\n", s, ratio, expected);
    }
}

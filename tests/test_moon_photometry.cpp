// The Moon as a planetarium shows it (shared/surface_photometry.glsl, passes/planet_light, body.frag):
//   - the lunar-Lambert disc integral in closed form against a numerical integral of the shared
//     function, and McEwen's L(alpha);
//   - Allen's phase curve: the full Moon at its mean distance is V = -12.74;
//   - the rendered Moon (the real map, real EGL) within 0.1 mag of Allen's curve from 0 to 120 deg;
//   - at full phase the disc is evenly bright out to its limb, where a Lambert sphere darkens;
//   - earthshine on a 3-day Moon against the full Moon and the lit limb, and none without the Earth.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "atmosphere/solar_scale.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "passes/planet_light.hpp"
#include "scene/planet_magnitude.hpp"
#include "scene/sky_positions.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "support/planet_frames.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

constexpr double kAu = kAstronomicalUnit_m;
constexpr double kMoonRadius_m = 1.7374e6, kMoonDistance_m = 3.844e8, kEarthRadius_m = 6.371e6;
const std::string kMoonMap = "/usr/share/openuniverse/textures/moon.jpg";

// A map of one linear grey everywhere (EXR: no sRGB decoding), so that only the photometry varies.
std::string uniform_map(const std::string& dir) {
    const std::string path = dir + "/uniform.exr";
    std::vector<float> px(64 * 32 * 3, 0.5f);
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(64, 32, 3, OIIO::TypeDesc::FLOAT)));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
    out->close();
    return path;
}

// The Sun (0), the Moon (1) and, with_earth, the Earth (2) as the body the Moon circles.
SceneConfig moon_scene(const std::string& dir, const std::string& texture, const std::string& photometry,
                       bool with_earth) {
    nlohmann::json bodies = {
        {{"name", "sun"}, {"kind", "star"}, {"ephemeris", "sun"}, {"radius_m", 6.957e8}, {"radiance", 5.8e4}},
        {{"name", "moon"},
         {"kind", "moon"},
         {"ephemeris", "moon"},
         {"radius_m", kMoonRadius_m},
         {"texture", texture},
         {"albedo", 0.35},
         {"photometry", photometry}}};
    nlohmann::json scene = {
        {"bodies", bodies},
        {"stars", {{"catalog", test::source_path("data/stars/bright_stars.csv")}, {"magnitude_limit", -2.0}}}};
    if (with_earth) {
        scene["bodies"].push_back({{"name", "earth"},
                                   {"kind", "planet"},
                                   {"ephemeris", "earth"},
                                   {"radius_m", kEarthRadius_m},
                                   {"texture", "generated:earth"},
                                   {"albedo", 0.3}});
        scene["shadows"] = {{"groups", {{{"parent", "earth"}, {"children", {"moon"}}}}}};
    }
    test::write_text(dir + "/scene.json", scene.dump());
    return load_scene_config(dir + "/scene.json");
}

// The Moon at the origin (pole +Z, its map's centre turned to the camera), the Sun 1 AU along +X,
// the camera at the Moon's mean distance at `phase_deg` from the Sun, looking at it with +Z up; the
// Earth, when the scene has it, just behind the camera (one radius under it).
Snapshot moon_view(double phase_deg, bool with_earth) {
    const double a = glm::radians(phase_deg);
    const glm::dvec3 to_camera(std::cos(a), std::sin(a), 0);
    Snapshot s;
    s.bodies.resize(with_earth ? 3 : 2);
    for (size_t i = 0; i < s.bodies.size(); ++i) s.bodies[i].id = static_cast<uint16_t>(i);
    s.bodies[0].position_m = glm::dvec3(kAu, 0.0, 0.0);
    s.bodies[1].orientation = glm::angleAxis(a, glm::dvec3(0, 0, 1));
    if (with_earth) s.bodies[2].position_m = to_camera * (kMoonDistance_m + 2.0 * kEarthRadius_m);
    s.camera_position_m = to_camera * kMoonDistance_m;
    s.settings.exposure = 0.0f;
    const glm::dvec3 back = to_camera, up(0, 0, 1), right = glm::normalize(glm::cross(up, back));
    s.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(back, right), back));
    return s;
}

// 256 pixels over 0.6 degrees: the Moon's disc (0.52 degrees) is 221 pixels across.
ChannelConfig moon_channel() { return test::straight_channel(0.3, 0.3, 256, 0.3); }

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

void headless() {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
}

// Each pixel of the disc with its surface normal's cosine to the Sun and to the camera (the shared
// view-ray and sphere functions, as body.frag has them).
struct DiscPixel {
    double luminance, cos_sun, cos_view;
};
std::vector<DiscPixel> disc_pixels(const Image& img, const ChannelConfig& ch, const Snapshot& s) {
    const ChannelFrustum f = ch.frustum();
    const glm::vec4 tangents(f.tan_left(), f.tan_right(), f.tan_down(), f.tan_up());
    const glm::dmat3 to_world = glm::mat3_cast(s.camera_orientation);
    const glm::dvec3 to_moon = -s.camera_position_m / glm::length(s.camera_position_m);
    const glm::vec3 centre(glm::transpose(to_world) * to_moon);
    const float sin_alpha = static_cast<float>(kMoonRadius_m / glm::length(s.camera_position_m));
    std::vector<DiscPixel> out;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec2 frag(x + 0.5f, img.height - y - 0.5f);
            const glm::vec3 v = shading::channel_ray(frag, glm::vec2(img.width, img.height), tangents);
            const glm::vec4 hit = shading::sphere_hit(v, centre, sin_alpha);
            if (hit.w < 0.0f) continue;
            const glm::dvec3 n = to_world * glm::dvec3(hit.x, hit.y, hit.z);
            out.push_back({luminance(img.pixel(x, y)), n.x, hit.w});
        }
    return out;
}

}  // namespace

TEST(MoonPhotometry, LunarLambertDiscIntegralMatchesTheSharedFunctionIntegrated) {
    // The disc integral of lunar_lambert x cos e over the sphere (unit radius), over its value for a
    // Lambert sphere at full phase (2 pi / 3).
    for (const double limb_weight : {0.0, 0.4, 1.0})
        for (const double phase_deg : {0.0, 30.0, 90.0, 150.0}) {
            const double a = glm::radians(phase_deg);
            const glm::dvec3 sun(1, 0, 0), eye(std::cos(a), std::sin(a), 0);
            const int n_lat = 400, n_lon = 800;
            double sum = 0.0;
            for (int i = 0; i < n_lat; ++i) {
                const double lat = ((i + 0.5) / n_lat - 0.5) * std::numbers::pi;
                for (int j = 0; j < n_lon; ++j) {
                    const double lon = (j + 0.5) / n_lon * 2.0 * std::numbers::pi;
                    const glm::dvec3 n(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
                    const double cos_e = glm::dot(n, eye);
                    if (cos_e <= 0.0) continue;
                    sum += shading::lunar_lambert(float(glm::dot(n, sun)), float(cos_e), float(limb_weight)) * cos_e *
                           std::cos(lat) * (std::numbers::pi / n_lat) * (2.0 * std::numbers::pi / n_lon);
                }
            }
            EXPECT_NEAR(sum / (2.0 * std::numbers::pi / 3.0) * 2.0 / 3.0, lunar_lambert_disc_integral(a, limb_weight),
                        2e-3)
                << "L " << limb_weight << ", phase " << phase_deg;
        }
    // McEwen's L: 1 at full phase, 0.186 at 90 degrees, 0 from about 104 degrees on.
    EXPECT_FLOAT_EQ(shading::lunar_lambert_limb_weight(0.0f), 1.0f);
    EXPECT_NEAR(shading::lunar_lambert_limb_weight(float(glm::radians(90.0))), 0.186, 1e-3);
    EXPECT_EQ(shading::lunar_lambert_limb_weight(float(glm::radians(120.0))), 0.0f);
}

TEST(MoonPhotometry, AllensCurveGivesTheFullMoonAtItsMeanDistance) {
    PlanetGeometry g;
    g.observer_distance_au = kMoonDistance_m / kAu;
    EXPECT_NEAR(*planet_magnitude_v("moon", g), -12.74, 0.01);
    // Quarter phase is 2.5 mag fainter (Allen: 0.026 x 90 + 4e-9 x 90^4 = 2.60).
    g.phase_deg = 90.0;
    EXPECT_NEAR(*planet_magnitude_v("moon", g), -12.74 + 2.60, 0.01);
}

TEST(MoonPhotometry, RenderedMoonFollowsAllensPhaseCurveFromZeroTo120Degrees) {
    headless();
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("moon_phase_curve");
    const SceneConfig scene = moon_scene(dir, kMoonMap, "lunar-lambert", false);
    const ChannelConfig ch = moon_channel();
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);
    const double sun_1au = atmosphere::sun_irradiance_scene_units(scene.bodies[0], kAu);
    for (const double a : {0.0, 2.0, 10.0, 30.0, 60.0, 90.0, 120.0}) {
        const Image img = renderer.render(moon_view(a, false));
        if (a == 0.0 || a == 60.0 || a == 120.0) test::maybe_write_frame("moon-phase-" + std::to_string(int(a)), img);
        const double rendered_v = kSunMagnitudeV - 2.5 * std::log10(test::frame_flux(img, ch) / sun_1au);
        PlanetGeometry g;
        g.observer_distance_au = kMoonDistance_m / kAu;
        g.phase_deg = a;
        const double curve_v = *planet_magnitude_v("moon", g);
        EXPECT_NEAR(rendered_v, curve_v, 0.1) << "phase " << a;
        std::printf("Moon phase %5.1f: rendered %+.3f, Allen %+.3f mag\n", a, rendered_v, curve_v);
    }
}

TEST(MoonPhotometry, FullMoonIsEvenlyBrightToItsLimbWhereALambertSphereDarkens) {
    headless();
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("moon_full_limb");
    const std::string map = uniform_map(dir);
    const ChannelConfig ch = moon_channel();
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    // The mean radiance of the pixels whose cos e lies near `mu`, over the disc centre's.
    auto limb_over_centre = [&](const std::string& photometry, double mu) {
        SceneRenderer renderer(cluster, ch, moon_scene(dir, map, photometry, false));
        const Snapshot s = moon_view(0.5, false);
        double centre = 0.0, limb = 0.0;
        int nc = 0, nl = 0;
        for (const DiscPixel& p : disc_pixels(renderer.render(s), ch, s)) {
            if (p.cos_view > 0.99) centre += p.luminance, ++nc;
            if (std::abs(p.cos_view - mu) < 0.02) limb += p.luminance, ++nl;
        }
        EXPECT_GT(nc, 10);
        EXPECT_GT(nl, 10);
        return (limb / nl) / (centre / nc);
    };
    const double lunar = limb_over_centre("lunar-lambert", 0.3), lambert = limb_over_centre("lambert", 0.3);
    std::printf("full Moon, radiance at cos e = 0.3 over the centre's: lunar-Lambert %.3f, Lambert %.3f\n", lunar,
                lambert);
    EXPECT_NEAR(lunar, 1.0, 0.05);
    EXPECT_NEAR(lambert, 0.3, 0.03);
}

// Earthshine on a 3-day Moon (37 degrees from the Sun, phase angle 143 degrees; the Earth, seen from
// the Moon, is then 37 degrees from full).
//   - Against the full Moon's radiance: about 1e-4 (the "ashen light" is 0.01 % of the full Moon's
//     light): within [3e-5, 3e-4].
//   - Against the crescent's lit limb (its brightest 1 %): the limb of a 143-degree crescent has only
//     about a quarter of the full Moon's radiance (Allen's curve: the disc is 5.4 mag fainter while
//     its lit area is 0.1 of the disc), so the ratio is about four times larger, 3.5e-4 with the
//     real map and 4.9e-4 with a uniform one: within [1e-4, 1e-3].
//   - Without the Earth the dark side is black.
TEST(MoonPhotometry, EarthshineOnAThreeDayMoonAgainstTheFullMoonAndItsLitLimb) {
    headless();
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("moon_earthshine");
    const std::string uniform = uniform_map(dir);
    const ChannelConfig ch = moon_channel();
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    struct Measured {
        double dark_median = 0.0, lit_limb = 0.0, centre = 0.0;
    };
    auto measure = [&](const std::string& texture, bool with_earth, double phase, const std::string& image) {
        SceneRenderer renderer(cluster, ch, moon_scene(dir, texture, "lunar-lambert", with_earth));
        const Snapshot s = moon_view(phase, with_earth);
        const Image img = renderer.render(s);
        std::vector<double> dark, lit, centre;
        for (const DiscPixel& p : disc_pixels(img, ch, s)) {
            if (p.cos_sun < -0.2 && p.cos_view > 0.3) dark.push_back(p.luminance);
            if (p.cos_sun > 0.05) lit.push_back(p.luminance);
            if (p.cos_view > 0.99) centre.push_back(p.luminance);
        }
        Measured m;
        std::sort(dark.begin(), dark.end());
        std::sort(lit.begin(), lit.end());
        if (!dark.empty()) m.dark_median = dark[dark.size() / 2];
        if (!lit.empty()) m.lit_limb = lit[lit.size() * 99 / 100];
        for (double c : centre) m.centre += c / static_cast<double>(centre.size());
        if (!image.empty()) test::maybe_write_frame(image, img, static_cast<float>(m.lit_limb * 1e-3));
        return m;
    };
    const double phase = 143.0;
    const Measured full = measure(uniform, false, 2.0, "");
    const Measured young = measure(uniform, true, phase, "");
    const Measured real = measure(kMoonMap, true, phase, "moon-earthshine-3day");
    const Measured alone = measure(kMoonMap, false, phase, "");
    ASSERT_GT(young.dark_median, 0.0);
    ASSERT_GT(full.centre, 0.0);
    const double of_full = young.dark_median / full.centre;
    std::printf("3-day Moon's earthshine: %.3g of the full Moon; of the lit limb %.3g (uniform map), %.3g (real map)\n",
                of_full, young.dark_median / young.lit_limb, real.dark_median / real.lit_limb);
    EXPECT_GT(of_full, 3e-5);
    EXPECT_LT(of_full, 3e-4);
    for (const Measured* m : {&young, &real}) {
        EXPECT_GT(m->dark_median / m->lit_limb, 1e-4);
        EXPECT_LT(m->dark_median / m->lit_limb, 1e-3);
    }
    EXPECT_GT(alone.lit_limb, 0.0);
    EXPECT_EQ(alone.dark_median, 0.0);
}

// The Milky Way (passes/milky_way_pass, shaders/milky_way.frag, shared/galactic_map.glsl):
//   - placed by the IAU galactic frame: a map's (l, b) = (0, 0) lands on the galactic centre's
//     published RA/Dec, and (90, 0) on Cygnus' side, each within a tenth of a degree;
//   - in the configured surface brightness (mag/arcsec^2, through the star field's zero_mag_flux);
//   - two half channels equal one wide channel (no seam);
//   - seen from the ground through the air: under one display level by day at the cluster's
//     exposure (the pass not even drawn), visible at night under a dark sky.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "atmosphere/auto_exposure.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "master_node.hpp"
#include "passes/milky_way_pass.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "show_script.hpp"
#include "support/planet_frames.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

// The galactic centre, (l, b) = (0, 0), and (90, 0) in the ICRS (the Hipparcos definition of the
// galactic frame: ESA 1997, volume 1, section 1.5.3): RA 17h45m37.20s, Dec -28d56m10.2s; RA
// 21h12m01.05s, Dec +48d19m46.7s.
constexpr double kCentreRa = 266.40500, kCentreDec = -28.93617;
constexpr double kCygnusRa = 318.00438, kCygnusDec = 48.32964;

glm::dvec3 unit_from_ra_dec(double ra_deg, double dec_deg) {
    const double a = glm::radians(ra_deg), d = glm::radians(dec_deg);
    return {std::cos(d) * std::cos(a), std::cos(d) * std::sin(a), std::sin(d)};
}

void headless() {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
}

// A 360 x 21 map of 1-degree texels (latitude extent 10.5 degrees) holding `value` everywhere and,
// when spots is set, 1000 in the two texels either side of (l, b) = (0, 0) and of (90, 0) (u = 0.5 -
// l / 360: l = 90 lies a quarter of the width to the left of the centre).
std::string write_map(const std::string& dir, float value, bool spots) {
    const int w = 360, h = 21;
    std::vector<float> px(static_cast<size_t>(w) * h * 3, value);
    if (spots)
        for (const int x : {179, 180, 89, 90})
            for (int c = 0; c < 3; ++c) px[(static_cast<size_t>(10) * w + x) * 3 + c] = 1000.0f;
    const std::string path = dir + "/map.exr";
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT)));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
    out->close();
    return path;
}

// The Sun far away out of the way and nothing else: the Milky Way and the stars (none brighter
// than -2) alone.
SceneConfig sky_scene(const std::string& dir, const std::string& map) {
    nlohmann::json scene = {
        {"bodies",
         {{{"name", "sun"}, {"kind", "star"}, {"ephemeris", "sun"}, {"radius_m", 6.957e8}, {"radiance", 2.0e9}}}},
        {"milky_way", {{"texture", map}, {"latitude_extent_deg", 10.5}, {"surface_brightness", 20.0}}},
        {"stars",
         {{"catalog", test::source_path("data/stars/bright_stars.csv")},
          {"magnitude_limit", -2.0},
          {"zero_mag_flux", 2.54e-6}}}};
    test::write_text(dir + "/scene.json", scene.dump());
    return load_scene_config(dir + "/scene.json");
}

// Looking along `dir` (world, unit) with `up` up.
glm::dquat looking_at(const glm::dvec3& dir, const glm::dvec3& up_hint) {
    const glm::dvec3 back = -dir, right = glm::normalize(glm::cross(up_hint, back));
    return glm::quat_cast(glm::dmat3(right, glm::cross(back, right), back));
}

Snapshot sky_view(const glm::dvec3& dir) {
    Snapshot s;
    s.bodies.resize(1);
    s.bodies[0].position_m = glm::dvec3(0.0, -1.5e11, 0.0);
    s.camera_orientation = looking_at(dir, glm::dvec3(0, 0, 1));
    s.settings.exposure = 0.0f;
    return s;
}

// The world direction of a frame's bright spot: the centroid of the pixels above a tenth of the
// brightest, weighted by their value.
glm::dvec3 bright_spot_direction(const Image& img, const ChannelConfig& ch, const Snapshot& s) {
    float best = 0.0f;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) best = std::max(best, img.pixel(x, y)[1]);
    const ChannelFrustum f = ch.frustum();
    const glm::vec4 tangents(f.tan_left(), f.tan_right(), f.tan_down(), f.tan_up());
    glm::dvec3 sum(0.0);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float value = img.pixel(x, y)[1];
            if (value < 0.1f * best) continue;
            const glm::vec2 frag(x + 0.5f, img.height - y - 0.5f);
            sum += double(value) * glm::dvec3(shading::channel_ray(frag, glm::vec2(img.width, img.height), tangents));
        }
    return glm::mat3_cast(s.camera_orientation) * glm::normalize(sum);
}

double degrees_between(const glm::dvec3& a, const glm::dvec3& b) {
    return glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)));
}

}  // namespace

TEST(MilkyWay, TheMapsOriginLandsOnTheGalacticCentreAndLongitudeRunsThroughCygnus) {
    headless();
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("milky_way_place");
    const SceneConfig scene = sky_scene(dir, write_map(dir, 0.001f, true));
    const ChannelConfig ch = test::straight_channel(5, 5, 256, 5);
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);
    for (const auto& [ra, dec, name] :
         {std::tuple{kCentreRa, kCentreDec, "galactic centre"}, std::tuple{kCygnusRa, kCygnusDec, "l = 90"}}) {
        const glm::dvec3 expected = unit_from_ra_dec(ra, dec);
        const Snapshot s = sky_view(expected);
        const double off = degrees_between(bright_spot_direction(renderer.render(s), ch, s), expected);
        std::printf("%s: the map's spot lands %.3f deg from its RA/Dec\n", name, off);
        EXPECT_LT(off, 0.1) << name;
    }
}

TEST(MilkyWay, ItsSurfaceBrightnessIsTheConfiguredOne) {
    headless();
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("milky_way_brightness");
    const SceneConfig scene = sky_scene(dir, write_map(dir, 0.25f, false));
    const ChannelConfig ch = test::straight_channel(5, 5, 64, 5, 64);
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);
    const Image img = renderer.render(sky_view(unit_from_ra_dec(kCentreRa, kCentreDec)));
    // 20 mag/arcsec^2: 2.54e-6 x 10^-8 per (pi / 648000)^2 sr.
    const double arcsec2 = std::pow(std::numbers::pi / 648000.0, 2.0);
    const double expected = 2.54e-6 * 1e-8 / arcsec2;
    EXPECT_NEAR(img.pixel(32, 32)[1], expected, 1e-3 * expected);
    EXPECT_NEAR(img.pixel(5, 60)[0], expected, 1e-3 * expected);
}

TEST(MilkyWay, TwoHalfChannelsEqualOneWideChannel) {
    headless();
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("milky_way_seam");
    const SceneConfig scene = sky_scene(dir, "/usr/share/openuniverse/textures/mw.jpg");
    const ChannelConfig left = test::straight_channel(20, 0, 128), right = test::straight_channel(0, 20, 128),
                        wide = test::straight_channel(20, 20, 256);
    ClusterConfig cluster;  // one cluster for all three: one coarsest pixel, one map level
    cluster.channels = {left, right, wide};
    SceneRenderer l(cluster, left, scene), r(cluster, right, scene), w(cluster, wide, scene);
    const Snapshot s = sky_view(unit_from_ra_dec(kCentreRa, kCentreDec));
    const Image a = l.render(s), b = r.render(s), c = w.render(s);
    double worst = 0.0, peak = 0.0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            const float* narrow = x < 128 ? a.pixel(x, y) : b.pixel(x - 128, y);
            worst = std::max(worst, double(std::abs(narrow[1] - c.pixel(x, y)[1])));
            peak = std::max(peak, double(c.pixel(x, y)[1]));
        }
    EXPECT_GT(peak, 0.0);
    EXPECT_LT(worst, 1e-4 * peak);
}

namespace {

// The planets-tonight night (Jena, 2026-12-18 23:00 UTC) with its dome's cluster and auto exposure,
// and the same snapshot with the Sun moved up to 10 degrees.
struct GroundNight {
    ClusterConfig cluster = load_cluster_config(test::source_path("configs/planets-tonight-dome.json"));
    SceneConfig scene = load_scene_config(cluster.scene_file);
    ShowScript show = ShowScript::load(cluster.show_file, scene);
    Snapshot night = make_frame_snapshot(cluster, scene, show, 0);
    Snapshot day() const {
        Snapshot s = night;
        const auto earth = scene.find("earth")->id, sun = scene.find("sun")->id;
        const glm::dvec3 up = glm::normalize(s.camera_position_m - s.bodies[earth].position_m);
        glm::dvec3 toward = s.bodies[sun].position_m - s.camera_position_m;
        toward = glm::normalize(toward - glm::dot(toward, up) * up);
        const double z = glm::radians(80.0);
        s.bodies[sun].position_m = s.camera_position_m + 1.496e11 * (std::cos(z) * up + std::sin(z) * toward);
        return s;
    }
};

}  // namespace

TEST(MilkyWay, UnderOneDisplayLevelByDayAndVisibleAtNight) {
    headless();
    EglContext gl(-1);
    GroundNight g;
    ASSERT_TRUE(g.scene.milky_way.present);
    SceneConfig without = g.scene;
    without.milky_way.present = false;
    // Cassiopeia's stretch of the band (l = 120, b = 0), high in the north-west that night.
    const ChannelConfig ch = test::straight_channel(20, 20, 96, 20, 96);
    ClusterConfig cluster;
    cluster.channels.push_back(ch);
    SceneRenderer with_band(cluster, ch, g.scene), no_band(cluster, ch, without);
    const AutoExposure exposure(g.cluster, g.scene);
    const glm::dvec3 up =
        glm::normalize(g.night.camera_position_m - g.night.bodies[g.scene.find("earth")->id].position_m);
    for (const bool is_day : {false, true}) {
        Snapshot s = is_day ? g.day() : g.night;
        s.camera_orientation = looking_at(unit_from_ra_dec(0.0, 62.0), up);
        s.settings.exposure = static_cast<float>(exposure.exposure(s));
        const Image a = with_band.render(s), b = no_band.render(s);
        double most = 0.0;
        for (size_t i = 0; i < a.rgba.size(); i += 4) most = std::max(most, double(a.rgba[i + 1] - b.rgba[i + 1]));
        const double display = most * s.settings.exposure;
        std::printf("%s: exposure %.3g, the band adds up to %.3g of the display\n", is_day ? "day" : "night",
                    s.settings.exposure, display);
        if (is_day)
            EXPECT_LT(display, 1.0 / 255.0);
        else
            EXPECT_GT(display, 4.0 / 255.0);
    }
}

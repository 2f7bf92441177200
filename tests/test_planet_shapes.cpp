// Oblate planets (BodyConfig::flattening): rendered in real EGL, the silhouette's extent along the
// pole over its extent along the equator is 1 - f when the pole lies in the sky plane (for an
// ellipse seen from a point in its plane the tangents are c / sqrt(d^2 - a^2) and
// a / sqrt(d^2 - a^2)), and 1 seen from over the pole, where the circle's tangent is
// a / sqrt(d^2 - c^2); a sphere gives 1 both ways. A flattened
// body with an atmosphere is refused by name.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "image/frame_image.hpp"
#include "scene_renderer.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

constexpr int kSize = 512;
constexpr double kRadius_m = 7.1492e7, kDistance_m = 2.4e8;

SceneConfig one_planet_scene(const std::string& dir, double flattening) {
    nlohmann::json scene = {
        {"bodies",
         {{{"name", "sun"}, {"kind", "star"}, {"ephemeris", "sun"}, {"radius_m", 6.957e8}, {"radiance", 5.8e4}},
          {{"name", "planet"},
           {"kind", "planet"},
           {"ephemeris", "jupiter"},
           {"radius_m", kRadius_m},
           {"flattening", flattening},
           {"texture", "generated:moon"},
           {"albedo", 1.0}}}},
        {"stars", {{"catalog", test::source_path("data/stars/bright_stars.csv")}, {"magnitude_limit", -2.0}}}};
    test::write_text(dir + "/scene.json", scene.dump());
    return load_scene_config(dir + "/scene.json");
}

// Pixels lit along the image's centre row and centre column.
glm::ivec2 lit_extent_px(const Image& img) {
    glm::ivec2 n(0);
    for (int i = 0; i < kSize; ++i) {
        n.x += img.pixel(i, kSize / 2)[0] > 0.0f;
        n.y += img.pixel(kSize / 2, i)[0] > 0.0f;
    }
    return n;
}

// The planet at the origin with its pole along world +Z, the Sun far behind the camera; the camera
// looks at the planet from `from` (unit), with world +Z (or +Y from over the pole) up.
Image render_planet(const SceneConfig& scene, const glm::dvec3& from) {
    ClusterConfig cluster;
    ChannelConfig ch;
    ch.fov = {30, 30, 30, 30};
    ch.width = ch.height = kSize;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);
    Snapshot s;
    s.bodies.resize(2);
    s.bodies[0].id = 0;
    s.bodies[1].id = 1;
    s.bodies[0].position_m = from * 1.5e11;
    s.camera_position_m = from * kDistance_m;
    const glm::dvec3 back = from, up = std::abs(from.z) > 0.5 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    const glm::dvec3 right = glm::normalize(glm::cross(up, back));
    s.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(back, right), back));
    return renderer.render(s);
}

}  // namespace

TEST(PlanetShapes, AnOblatePlanetsSilhouetteIsOneMinusFlatteningAcrossThePole) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    EglContext gl(-1);
    const std::string dir = test::scratch_dir("planet_shapes");
    // Expected equatorial extent: 2 tan(alpha) over the 2 tan(30 deg) the channel spans.
    auto extent_px = [](double tangent) { return kSize * tangent / std::tan(glm::radians(30.0)); };
    const double d2 = kDistance_m * kDistance_m,
                 equator_px = extent_px(kRadius_m / std::sqrt(d2 - kRadius_m * kRadius_m));
    for (const double f : {0.0, 0.06487, 0.09796}) {
        const double c = kRadius_m * (1.0 - f), over_pole_px = extent_px(kRadius_m / std::sqrt(d2 - c * c));
        const SceneConfig scene = one_planet_scene(dir, f);
        const glm::ivec2 side = lit_extent_px(render_planet(scene, glm::dvec3(1, 0, 0)));
        EXPECT_NEAR(side.x, equator_px, 2.0) << "f = " << f;
        EXPECT_NEAR(double(side.y) / side.x, 1.0 - f, 2.5 / side.x) << "f = " << f;
        const glm::ivec2 pole = lit_extent_px(render_planet(scene, glm::dvec3(0, 0, 1)));
        EXPECT_NEAR(double(pole.y) / pole.x, 1.0, 2.5 / pole.x) << "f = " << f;
        EXPECT_NEAR(pole.x, over_pole_px, 2.0) << "f = " << f;
    }
}

TEST(PlanetShapes, AFlattenedBodyWithAnAtmosphereIsRefused) {
    const std::string dir = test::scratch_dir("planet_shapes_refused");
    nlohmann::json scene = nlohmann::json::parse(test::read_text(test::source_path("configs/scenes/earth-moon.json")));
    scene["bodies"][1]["flattening"] = 0.00335;
    scene["stars"]["catalog"] = test::source_path("data/stars/bright_stars.csv");
    if (scene.contains("overlays")) scene["overlays"]["figures"] = test::source_path("data/sky/constellations.json");
    test::write_text(dir + "/scene.json", scene.dump());
    try {
        load_scene_config(dir + "/scene.json");
        FAIL() << "a flattened body with an atmosphere was accepted";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("flattening"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("atmosphere"), std::string::npos) << e.what();
    }
}

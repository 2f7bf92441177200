// Precision: positions are double on the CPU and the GPU sees camera-relative floats only, so
// the image depends on relative geometry alone. The Earth seen from the Moon's distance, with the
// whole scene 1 AU from the origin, must render exactly as the same scene near the origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/egl_context.hpp"
#include "scene_renderer.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

Image render_at(SceneRenderer& r, const Snapshot& base, const glm::dvec3& shift) {
    Snapshot s = base;
    s.camera_position_m += shift;
    for (auto& b : s.bodies) b.position_m += shift;
    return r.render(s);
}

double max_abs_diff(const Image& a, const Image& b) {
    double m = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) m = std::max(m, std::abs(double(a.rgba[i]) - b.rgba[i]));
    return m;
}

}  // namespace

TEST(Precision, EarthFromTheMoonDoesNotDependOnDistanceFromTheOrigin) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    EglContext gl(-1);
    SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    ClusterConfig cluster;
    ChannelConfig ch;
    ch.id = 0;
    ch.name = "narrow";
    ch.fov = {1.2, 1.2, 1.2, 1.2};  // 2.4 degrees: the Earth (1.9 degrees from the Moon) fills it
    ch.width = ch.height = 96;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);

    // Camera at the Moon's distance from the Earth, looking at it; the Sun off to the side.
    const uint16_t sun = scene.find("sun")->id, earth = scene.find("earth")->id, moon = scene.find("moon")->id;
    Snapshot s;
    s.bodies.resize(scene.bodies.size());
    for (auto& b : s.bodies) b.id = static_cast<uint16_t>(&b - s.bodies.data());
    const glm::dvec3 earth_pos(0.0, 0.0, 0.0);
    s.bodies[earth].position_m = earth_pos;
    s.bodies[sun].position_m = glm::dvec3(0.3e11, -1.496e11, 0.0);       // behind the camera: a nearly full Earth
    s.bodies[moon].position_m = glm::dvec3(0.0, -3.844e8 - 5.0e6, 0.0);  // behind the camera
    s.camera_position_m = glm::dvec3(0.0, -3.844e8, 0.0);
    // Camera -Z towards +Y (the Earth), +Y up along world +Z.
    s.camera_orientation = glm::quat_cast(glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, -1, 0)));

    const Image near_origin = render_at(renderer, s, glm::dvec3(0.0));
    // The Earth is in the picture: a lit disc filling most of the channel.
    int lit = 0;
    for (int y = 0; y < near_origin.height; ++y)
        for (int x = 0; x < near_origin.width; ++x)
            lit +=
                std::max({near_origin.pixel(x, y)[0], near_origin.pixel(x, y)[1], near_origin.pixel(x, y)[2]}) > 1e-5f;
    EXPECT_GT(lit, near_origin.width * near_origin.height / 4);

    // The same scene moved 1 AU (and 40 AU) away from the origin, with odd metre fractions.
    const glm::dvec3 one_au(-1.3e11, 7.4e10, 1.2345678e9 + 0.37);
    const Image far = render_at(renderer, s, one_au);
    EXPECT_LE(max_abs_diff(near_origin, far), 1e-6);
    const Image very_far = render_at(renderer, s, one_au * 40.0);
    EXPECT_LE(max_abs_diff(near_origin, very_far), 1e-6);

    // Whereas moving the camera by 1/4 of a pixel (relative geometry changes) is visible:
    // the test can tell a shift far smaller than float spacing at 1 AU (about 16 km) would make.
    const double pixel_m = glm::radians(2.4) / 96 * 3.844e8;
    Snapshot moved = s;
    moved.camera_position_m.x += 0.25 * pixel_m;
    const Image shifted = render_at(renderer, moved, one_au);
    EXPECT_GT(max_abs_diff(near_origin, shifted), 1e-3);
}

// Textured bodies are not mirrored or rotated: seen from space above longitude 0 with north up,
// east longitudes are on the right and the northern hemisphere is on top (a test texture marks
// west red, east green and north blue).
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

TEST(BodyOrientation, EastIsRightAndNorthIsUpFromAboveLongitudeZero) {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    const std::string dir = test::scratch_dir("body_orientation");
    Image tex;
    tex.width = 64;
    tex.height = 32;
    tex.rgba.assign(64 * 32 * 4, 0.0f);
    for (int y = 0; y < tex.height; ++y)
        for (int x = 0; x < tex.width; ++x) {
            const double lon = ((x + 0.5) / tex.width - 0.5) * 360.0, lat = (0.5 - (y + 0.5) / tex.height) * 180.0;
            float* p = tex.pixel(x, y);
            p[0] = lon < 0 ? 1.0f : 0.0f;
            p[1] = lon > 0 ? 1.0f : 0.0f;
            p[2] = lat > 0 ? 1.0f : 0.0f;
            p[3] = 1.0f;
        }
    const std::string tex_path = write_frame(dir, tex, FrameMetadata{}, {"png"}, 1.0).at(0);
    nlohmann::json scene_json =
        nlohmann::json::parse(test::read_text(test::source_path("configs/scenes/earth-moon.json")));
    scene_json["bodies"][1]["texture"] = tex_path;
    scene_json["bodies"][1].erase("atmosphere");  // the texture's own colours, not the sky's haze
    scene_json["stars"]["catalog"] = test::source_path("data/stars/bright_stars.csv");
    if (scene_json.contains("overlays"))
        scene_json["overlays"]["figures"] = test::source_path("data/sky/constellations.json");
    scene_json["stars"]["magnitude_limit"] = -2.0;  // no stars in this picture
    test::write_text(dir + "/scene.json", scene_json.dump());
    const SceneConfig scene = load_scene_config(dir + "/scene.json");

    EglContext gl(-1);
    ClusterConfig cluster;
    ChannelConfig ch;
    ch.fov = {30, 30, 30, 30};
    ch.width = ch.height = 64;
    cluster.channels.push_back(ch);
    SceneRenderer renderer(cluster, ch, scene);

    Snapshot s;
    const uint16_t sun = scene.find("sun")->id, earth = scene.find("earth")->id, moon = scene.find("moon")->id;
    s.bodies.resize(scene.bodies.size());
    for (auto& b : s.bodies) b.id = static_cast<uint16_t>(&b - s.bodies.data());
    const glm::dvec3 e(-1.496e11, 0.0, 0.0);  // body frame = world frame (prime meridian along +X)
    s.bodies[earth].position_m = e;
    s.bodies[sun].position_m = glm::dvec3(0.0);                  // the Sun lights longitude 0 (on +X)
    s.bodies[moon].position_m = e + glm::dvec3(0.0, 0.0, -4e8);  // out of view
    s.camera_position_m = e + glm::dvec3(3.0e7, 0.0, 0.0);
    // Camera looks along world -X, up along world +Z (north), so right is world +Y (longitude +90).
    s.camera_orientation = glm::quat_cast(glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0)));
    const Image img = renderer.render(s);

    auto mean = [&](int x0, int x1, int y0, int y1) {
        glm::dvec3 m(0.0);
        int n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x, ++n)
                m += glm::dvec3(img.pixel(x, y)[0], img.pixel(x, y)[1], img.pixel(x, y)[2]);
        return m / double(n);
    };
    const glm::dvec3 right = mean(40, 48, 28, 36), left = mean(16, 24, 28, 36);
    const glm::dvec3 top = mean(28, 36, 16, 24), bottom = mean(28, 36, 40, 48);
    EXPECT_GT(right.g, 10.0 * right.r) << "east (green) should be on the right";
    EXPECT_GT(left.r, 10.0 * left.g) << "west (red) should be on the left";
    EXPECT_GT(top.b, 10.0 * bottom.b + 1e-6) << "north (blue) should be on top";
    EXPECT_GT(top.b, 0.01);
}

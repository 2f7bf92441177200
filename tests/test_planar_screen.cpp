// Channels given as flat screens in the room (common/projection/planar_screen, Kooima 2008): the
// off-axis frustum from the eye through the screen's corners, its orientation's round trip, and
// the config errors that name what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "projection/dome_frame.hpp"
#include "projection/planar_screen.hpp"
#include "support/test_support.hpp"

using namespace cupola;
using nlohmann::json;

namespace {

constexpr double kDeg = 57.29577951308232;

// The pixel (x right, y down, in pixels) a room point is seen at through a channel from the eye.
glm::dvec2 seen_at(const ChannelFrustum& f, const glm::dvec3& eye, const glm::dvec3& point) {
    const auto p = f.dome_direction_to_pixel(glm::normalize(point - eye));
    EXPECT_TRUE(p.has_value());
    return p.value_or(glm::dvec2(-1.0));
}

}  // namespace

TEST(PlanarScreen, EulerAnglesRoundTrip) {
    for (double yaw : {-170.0, -90.0, 0.0, 35.0, 90.0, 179.0})
        for (double pitch : {-89.0, -40.0, 0.0, 60.0})
            for (double roll : {-120.0, 0.0, 15.0, 180.0}) {
                const glm::dmat3 m = channel_rotation({yaw, pitch, roll});
                const glm::dmat3 back = channel_rotation(euler_of(m));
                for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(back[c] - m[c]), 1e-12) << yaw << " " << pitch;
            }
}

// A 4 x 3 m screen 2 m in front of the eye: its corners are the corners of the image, from the
// centre and from an eye 1 m to the left and 0.5 m down, where the frustum leans off its axis.
TEST(PlanarScreen, TheScreensCornersAreTheImagesCornersWhereverTheEyeIs) {
    const PlanarScreen front{{-2.0, -1.5, -2.0}, {-2.0, 1.5, -2.0}, {2.0, 1.5, -2.0}};
    const glm::dvec3 lower_right(2.0, -1.5, -2.0);
    for (const glm::dvec3 eye : {glm::dvec3(0.0), glm::dvec3(-1.0, -0.5, 0.0), glm::dvec3(0.3, 0.2, 1.0)}) {
        const ScreenFrustum s = screen_frustum(front, eye);
        EXPECT_NEAR(s.orientation.yaw_deg, 0.0, 1e-9);
        EXPECT_NEAR(s.orientation.pitch_deg, 0.0, 1e-9);
        EXPECT_NEAR(s.orientation.roll_deg, 0.0, 1e-9);
        const ChannelFrustum f(s.orientation, s.fov, 400, 300);
        const glm::dvec2 ll = seen_at(f, eye, front.lower_left_m), ur = seen_at(f, eye, front.upper_right_m);
        const glm::dvec2 ul = seen_at(f, eye, front.upper_left_m), lr = seen_at(f, eye, lower_right);
        EXPECT_NEAR(glm::length(ll - glm::dvec2(0.0, 300.0)), 0.0, 1e-6);
        EXPECT_NEAR(glm::length(ul - glm::dvec2(0.0, 0.0)), 0.0, 1e-6);
        EXPECT_NEAR(glm::length(ur - glm::dvec2(400.0, 0.0)), 0.0, 1e-6);
        EXPECT_NEAR(glm::length(lr - glm::dvec2(400.0, 300.0)), 0.0, 1e-6);
        // A point of the screen lands where it lies on it (the screen's pixels are square here).
        const glm::dvec2 p = seen_at(f, eye, glm::dvec3(1.0, 0.5, -2.0));
        EXPECT_NEAR(p.x, 300.0, 1e-6);
        EXPECT_NEAR(p.y, 100.0, 1e-6);
    }
    const ScreenFrustum centred = screen_frustum(front, glm::dvec3(0.0));
    EXPECT_NEAR(centred.fov.left_deg, std::atan(1.0) * kDeg, 1e-9);
    EXPECT_NEAR(centred.fov.up_deg, std::atan(0.75) * kDeg, 1e-9);
    const ScreenFrustum off = screen_frustum(front, glm::dvec3(-1.0, -0.5, 0.0));
    EXPECT_NEAR(off.fov.left_deg, std::atan(0.5) * kDeg, 1e-9);
    EXPECT_NEAR(off.fov.right_deg, std::atan(1.5) * kDeg, 1e-9);
    EXPECT_NEAR(off.fov.down_deg, std::atan(0.5) * kDeg, 1e-9);
    EXPECT_NEAR(off.fov.up_deg, std::atan(1.0) * kDeg, 1e-9);
}

// A CAVE's left wall and floor (a 3 m cube around an eye 1.5 m from every wall, 1.2 m up): turned
// 90 degrees left, and looking down with the front wall at the top.
TEST(PlanarScreen, ACavesLeftWallAndFloor) {
    const glm::dvec3 eye(0.0, 1.2, 0.0);
    const PlanarScreen left{{-1.5, 0.0, 1.5}, {-1.5, 3.0, 1.5}, {-1.5, 3.0, -1.5}};
    const ScreenFrustum l = screen_frustum(left, eye);
    EXPECT_NEAR(l.orientation.yaw_deg, -90.0, 1e-9);
    EXPECT_NEAR(l.orientation.pitch_deg, 0.0, 1e-9);
    EXPECT_NEAR(l.fov.left_deg, 45.0, 1e-9);
    EXPECT_NEAR(l.fov.up_deg, std::atan(1.8 / 1.5) * kDeg, 1e-9);
    const PlanarScreen floor{{-1.5, 0.0, 1.5}, {-1.5, 0.0, -1.5}, {1.5, 0.0, -1.5}};
    const ScreenFrustum d = screen_frustum(floor, eye);
    EXPECT_NEAR(d.orientation.pitch_deg, -90.0, 1e-9);
    const glm::dmat3 m = channel_rotation(d.orientation);
    EXPECT_LT(glm::length(m[1] - glm::dvec3(0.0, 0.0, -1.0)), 1e-9) << "the image's up is toward the front wall";
    EXPECT_NEAR(d.fov.left_deg, std::atan(1.5 / 1.2) * kDeg, 1e-9);
}

TEST(PlanarScreen, BadScreensAreRefusedSayingWhy) {
    const PlanarScreen front{{-2.0, -1.5, -2.0}, {-2.0, 1.5, -2.0}, {2.0, 1.5, -2.0}};
    const auto refused = [](const PlanarScreen& s, const glm::dvec3& eye, const std::string& words) {
        try {
            screen_frustum(s, eye);
            ADD_FAILURE() << "no error: " << words;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    refused(front, glm::dvec3(0.0, 0.0, -3.0), "behind");
    refused(front, glm::dvec3(0.0, 0.0, -2.0), "on the screen's plane");
    refused({front.lower_left_m, front.upper_left_m, front.upper_left_m}, glm::dvec3(0.0), "coincide");
    refused({{-2.0, -1.5, -2.0}, {-2.0, 1.5, -2.0}, {2.0, 1.8, -2.0}}, glm::dvec3(0.0), "rectangle");
    refused({{-200.0, -1.5, -2.0}, {-200.0, 1.5, -2.0}, {2.0, 1.5, -2.0}}, glm::dvec3(0.0), "89");
}

// In a cluster file: a flat three-screen wall; the screens' orientation and fov follow from the
// corners and room.eye_m; errors name the file and the field.
TEST(PlanarScreen, AWallOfThreeScreensFromItsConfig) {
    const std::string dir = test::scratch_dir("planar_screen_wall");
    json cfg = json::parse(test::read_text(test::source_path("configs/wall-3ch.json")));
    for (const char* k : {"key_file", "scene", "show"})
        cfg[k] = test::source_path("configs/" + cfg[k].get<std::string>());
    cfg["room"] = {{"eye_m", {0.0, 1.6, 2.0}}};
    cfg["channels"] = json::array();
    for (int i = 0; i < 3; ++i) {
        const double x0 = -3.0 + 2.0 * i, x1 = x0 + 2.0;  // three 2 x 1.125 m screens side by side at z = 0
        cfg["channels"].push_back({{"id", i},
                                   {"screen",
                                    {{"lower_left_m", {x0, 1.0, 0.0}},
                                     {"upper_left_m", {x0, 2.125, 0.0}},
                                     {"upper_right_m", {x1, 2.125, 0.0}}}}});
    }
    const std::string path = dir + "/wall.json";
    test::write_text(path, cfg.dump(2));
    const ClusterConfig c = load_cluster_config(path);
    ASSERT_EQ(c.channels.size(), 3u);
    for (const ChannelConfig& ch : c.channels) {
        ASSERT_TRUE(ch.screen.has_value());
        EXPECT_NEAR(ch.orientation.yaw_deg, 0.0, 1e-9) << "a flat wall: every channel looks straight ahead";
        EXPECT_NEAR(ch.fov.up_deg, std::atan(0.525 / 2.0) * kDeg, 1e-9);
    }
    EXPECT_NEAR(c.channels[0].fov.left_deg, std::atan(3.0 / 2.0) * kDeg, 1e-9);
    EXPECT_NEAR(c.channels[0].fov.right_deg, -std::atan(1.0 / 2.0) * kDeg, 1e-9);  // wholly left of the axis
    EXPECT_NEAR(c.channels[1].fov.left_deg, c.channels[1].fov.right_deg, 1e-12);
    // The eye behind the wall: refused, naming the channel's screen.
    cfg["room"]["eye_m"] = {0.0, 1.6, -1.0};
    test::write_text(path, cfg.dump(2));
    try {
        load_cluster_config(path);
        FAIL() << "no error for an eye behind the screens";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "channels[0].screen") << e.what();
        EXPECT_NE(std::string(e.what()).find("behind"), std::string::npos) << e.what();
    }
}

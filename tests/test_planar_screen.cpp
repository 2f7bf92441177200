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

namespace {

// The point of a screen where a channel's continuous pixel lies (the screen fills the image).
glm::dvec3 screen_point(const PlanarScreen& s, const ChannelFrustum& f, const glm::dvec2& px) {
    return s.upper_left_m + (px.x / f.width()) * (s.upper_right_m - s.upper_left_m) +
           (px.y / f.height()) * (s.lower_left_m - s.upper_left_m);
}

// The shipped CAVE's channels, the paths in the file made absolute.
ClusterConfig shipped_cave() {
    const std::string dir = test::scratch_dir("planar_screen_cave");
    json cfg = json::parse(test::read_text(test::source_path("configs/cave-4wall.json")));
    for (const char* k : {"key_file", "scene", "show"})
        cfg[k] = test::source_path("configs/" + cfg[k].get<std::string>());
    test::write_text(dir + "/cave.json", cfg.dump(2));
    return load_cluster_config(dir + "/cave.json");
}

}  // namespace

// A head off centre in the 3 m CAVE (0.6 m right, 0.4 m low, 0.9 m back): a straight line in the
// room behind the front-left corner, seen through the front and the left screens, is drawn on the
// walls in the plane through the eye and the line (straight) and meets itself at the corner
// (continuous), both within 0.5 px, with each channel's frustum following the head.
TEST(PlanarScreen, AStraightLineStaysStraightAcrossACavesCornerForAHeadOffCentre) {
    const ClusterConfig cave = shipped_cave();
    const ChannelConfig& front = cave.channels[0];
    const ChannelConfig& left = cave.channels[1];
    const glm::dvec3 eye(0.6, 1.3, 0.9);
    const ChannelFrustum ff = front.frustum_seen_from(eye), lf = left.frustum_seen_from(eye);
    EXPECT_NE(ff.fov().left_deg, front.fov.left_deg) << "the frustum follows the head";
    const glm::dvec3 a(0.5, 0.4, -4.0), b(-4.0, 2.6, 0.8);  // the line, outside the cube
    const glm::dvec3 plane_normal = glm::normalize(glm::cross(a - eye, b - eye));
    double worst_plane_px = 0.0;
    int on_front = 0, on_left = 0;
    for (int i = 0; i <= 400; ++i) {
        const glm::dvec3 dir = glm::normalize(glm::mix(a, b, i / 400.0) - eye);
        for (const auto* ch : {&front, &left}) {
            const ChannelFrustum& f = ch == &front ? ff : lf;
            if (!f.contains(dir)) continue;
            const glm::dvec3 on_wall = screen_point(*ch->screen, f, *f.dome_direction_to_pixel(dir));
            const double px_m = 3.0 / f.width();  // the screens are 3 m wide
            worst_plane_px = std::max(worst_plane_px, std::abs(glm::dot(on_wall - eye, plane_normal)) / px_m);
            ++(ch == &front ? on_front : on_left);
        }
    }
    EXPECT_GT(on_front, 20);
    EXPECT_GT(on_left, 20);
    EXPECT_LT(worst_plane_px, 0.5);
    // Where the line's sight crosses the corner (x = z = -1.5), both channels put it at the same
    // point of the corner edge.
    const double s = [&] {  // the mix parameter whose sight passes through the corner's vertical line
        double lo = 0.0, hi = 1.0;
        for (int k = 0; k < 80; ++k) {
            const double mid = 0.5 * (lo + hi);
            const glm::dvec3 d = glm::mix(a, b, mid) - eye;
            // Sight to the corner's vertical line: where d.x / d.z equals that of the corner.
            ((d.x * (-1.5 - eye.z) - d.z * (-1.5 - eye.x)) > 0.0 ? hi : lo) = mid;
        }
        return 0.5 * (lo + hi);
    }();
    const glm::dvec3 corner_dir = glm::normalize(glm::mix(a, b, s) - eye);
    const glm::dvec3 via_front = screen_point(*front.screen, ff, *ff.dome_direction_to_pixel(corner_dir));
    const glm::dvec3 via_left = screen_point(*left.screen, lf, *lf.dome_direction_to_pixel(corner_dir));
    EXPECT_LT(glm::length(via_front - via_left) / (3.0 / ff.width()), 0.5);
    EXPECT_NEAR(via_front.x, -1.5, 1e-6);
    EXPECT_NEAR(via_front.z, -1.5, 1e-6);
}

// Channels given by angles (a dome, the angle-based wall) keep their configured frusta wherever
// the head is: the head moves only screens.
TEST(PlanarScreen, AngleBasedChannelsKeepTheirFrustaWhereverTheHeadIs) {
    json cfg = json::parse(test::read_text(test::source_path("configs/wall-3ch.json")));
    for (const char* k : {"key_file", "scene", "show"})
        cfg[k] = test::source_path("configs/" + cfg[k].get<std::string>());
    const std::string path = test::scratch_dir("planar_screen_angles") + "/wall.json";
    test::write_text(path, cfg.dump(2));
    const ClusterConfig c = load_cluster_config(path);
    for (const ChannelConfig& ch : c.channels)
        for (const glm::dvec3 eye : {glm::dvec3(0.0), glm::dvec3(0.4, -0.3, 1.0)}) {
            const ChannelFrustum f = ch.frustum_seen_from(eye), g = ch.frustum();
            EXPECT_EQ(f.tan_left(), g.tan_left());
            EXPECT_EQ(f.tan_right(), g.tan_right());
            EXPECT_EQ(f.tan_up(), g.tan_up());
            EXPECT_EQ(f.tan_down(), g.tan_down());
            EXPECT_EQ(f.orientation().yaw_deg, g.orientation().yaw_deg);
        }
    // A screen seen from an eye behind it keeps its configured frustum rather than failing.
    const ClusterConfig cave = shipped_cave();
    const ChannelFrustum kept = cave.channels[0].frustum_seen_from(glm::dvec3(0.0, 1.5, -2.0));
    EXPECT_EQ(kept.tan_left(), cave.channels[0].frustum().tan_left());
}

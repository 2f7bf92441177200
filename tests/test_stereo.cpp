// Stereo for VR walls and CAVEs (projection/stereo_mode, slave/stereo_packer, the renderer's eyes):
// a planet on the screen's plane has no disparity; in front of it or behind it, the disparity the
// geometry of the eyes and the screen predicts; a star's rays are parallel in both eyes; the
// packings put each eye where they say; the anaglyph is Dubois's matrices of the two eyes; a
// loopback wall renders both eyes of a frame from one snapshot.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "image/frame_image.hpp"
#include "projection/stereo_mode.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "support/headless_gl.hpp"
#include "support/loopback_run.hpp"
#include "support/planet_frames.hpp"
#include "support/test_support.hpp"

using namespace cupola;
using nlohmann::json;

namespace {

constexpr int kEye = 160;             // pixels per eye, each way, over the 1 m screen
constexpr double kScale = 1e7;        // scene metres per room metre
constexpr double kRadius_m = 1.74e6;  // the planet: 0.174 room metres
constexpr double kScreenZ = -2.0;     // the screen 2 m in front of the head
constexpr double kSeparation_m = 0.064;

SceneConfig planet_and_sun(const std::string& dir) {
    json scene = {
        {"bodies",
         {{{"name", "sun"}, {"kind", "star"}, {"ephemeris", "sun"}, {"radius_m", 6.957e8}, {"radiance", 5.8e4}},
          {{"name", "planet"},
           {"kind", "planet"},
           {"ephemeris", "jupiter"},
           {"radius_m", kRadius_m},
           {"texture", "generated:moon"},
           {"albedo", 1.0}}}},
        {"stars", {{"catalog", dir + "/one_star.csv"}, {"magnitude_limit", 6.5}}}};
    // One bright star 3 degrees right of straight ahead (RA 87, Dec 0: the camera looks at RA 90).
    test::write_text(dir + "/one_star.csv", "ra_deg,dec_deg,vmag,bv,name\n87.0,0.0,-1.0,0.65,Test\n");
    test::write_text(dir + "/scene.json", scene.dump());
    return load_scene_config(dir + "/scene.json");
}

// The head at the room's origin, a 1 m square screen 2 m in front of it.
ClusterConfig wall(StereoMode mode) {
    ClusterConfig c;
    c.room.scale = kScale;
    c.room.eye_separation_m = kSeparation_m;
    ChannelConfig ch;
    ch.screen = PlanarScreen{{-0.5, -0.5, kScreenZ}, {-0.5, 0.5, kScreenZ}, {0.5, 0.5, kScreenZ}};
    const ScreenFrustum f = screen_frustum(*ch.screen, glm::dvec3(0.0));
    ch.orientation = f.orientation, ch.fov = f.fov;
    ch.width = ch.height = kEye;
    ch.stereo = mode;
    c.channels = {ch};
    return c;
}

// The camera at the world's origin looking along world +y (RA 90, Dec 0), world +z up; the planet
// `room_distance_m` in front of the head; the Sun far behind the camera; no star drawn.
Snapshot planet_at(double room_distance_m) {
    Snapshot s;
    s.bodies.resize(2);
    s.bodies[0].id = 0;
    s.bodies[1].id = 1;
    s.bodies[0].position_m = glm::dvec3(0.0, -1.5e11, 0.0);
    s.bodies[1].position_m = glm::dvec3(0.0, room_distance_m * kScale, 0.0);
    s.camera_orientation = glm::quat_cast(glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, -1, 0)));
    s.settings.star_magnitude_limit = -30.0f;  // no star: the planet alone
    return s;
}

// The centre of what is lit in columns [x0, x0 + w) of the frame (x right, y down): of the pixels
// brighter than 5 % of the brightest there, each counted once (a disc's silhouette), or weighted by
// its green (a star's image).
glm::dvec2 lit_centre(const Image& img, int x0, int w, bool weighted = false) {
    float peak = 0.0f;
    for (int y = 0; y < img.height; ++y)
        for (int x = x0; x < x0 + w; ++x) peak = std::max(peak, img.pixel(x, y)[1]);
    glm::dvec2 sum(0.0);
    double n = 0.0;
    for (int y = 0; y < img.height; ++y)
        for (int x = x0; x < x0 + w; ++x) {
            const float g = img.pixel(x, y)[1];
            if (!(g > 0.05f * peak)) continue;
            const double weight = weighted ? g : 1.0;
            sum += weight * glm::dvec2(x - x0 + 0.5, y + 0.5), n += weight;
        }
    EXPECT_GT(n, 0.0) << "nothing lit";
    return n > 0.0 ? sum / n : glm::dvec2(-1.0);
}

// Where the line from the eye to a room point meets the screen, as a pixel of that eye's image.
glm::dvec2 predicted_pixel(double eye_x_m, const glm::dvec3& point) {
    const glm::dvec3 eye(eye_x_m, 0.0, 0.0);
    const glm::dvec3 hit = eye + (point - eye) * ((kScreenZ - eye.z) / (point.z - eye.z));
    return {(hit.x + 0.5) * kEye, (0.5 - hit.y) * kEye};
}

}  // namespace

TEST(Stereo, ModesSayWhereEachEyeLies) {
    EXPECT_EQ(stereo_eye_count(StereoMode::Mono), 1);
    EXPECT_EQ(stereo_eye_count(StereoMode::Right), 1);
    EXPECT_EQ(stereo_eye_count(StereoMode::Anaglyph), 2);
    EXPECT_EQ(stereo_eye_side(StereoMode::Left, 0), -1.0);
    EXPECT_EQ(stereo_eye_side(StereoMode::TopBottom, 1), 1.0);
    EXPECT_EQ(stereo_frame_size(StereoMode::SideBySide, 100, 50), glm::ivec2(200, 50));
    EXPECT_EQ(stereo_frame_size(StereoMode::TopBottomHalf, 100, 50), glm::ivec2(100, 50));
    EXPECT_EQ(stereo_eye_size(StereoMode::SideBySideHalf, 100, 50), glm::ivec2(50, 50));
    EXPECT_EQ(stereo_eye_viewport(StereoMode::SideBySide, 1, 100, 50), glm::ivec4(100, 0, 100, 50));
    EXPECT_EQ(stereo_eye_viewport(StereoMode::TopBottom, 0, 100, 50), glm::ivec4(0, 50, 100, 50));  // on top
    EXPECT_EQ(stereo_mode_from_name("top_bottom_half"), StereoMode::TopBottomHalf);
    try {
        stereo_mode_from_name("quad_buffer");
        FAIL() << "quad_buffer accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("EGL"), std::string::npos) << e.what();
    }
}

TEST(Stereo, TheConfigGivesEachChannelItsStereoAndRefusesWhatCannotBe) {
    const std::string dir = test::scratch_dir("stereo_config");
    json cfg = json::parse(test::read_text(test::source_path("configs/wall-3screen-stereo.json")));
    for (const char* k : {"key_file", "scene", "show"})
        cfg[k] = test::source_path("configs/" + cfg[k].get<std::string>());
    cfg["channels"][2]["stereo"] = "anaglyph";
    test::write_text(dir + "/wall.json", cfg.dump(2));
    const ClusterConfig c = load_cluster_config(dir + "/wall.json");
    EXPECT_EQ(c.channels[0].stereo, StereoMode::SideBySide);
    EXPECT_EQ(c.channels[2].stereo, StereoMode::Anaglyph);
    EXPECT_DOUBLE_EQ(c.room.eye_separation_m, 0.064);
    const auto refused = [&](const json& change, const std::string& field, const std::string& words) {
        json bad = cfg;
        bad.merge_patch(change);
        test::write_text(dir + "/bad.json", bad.dump(2));
        try {
            load_cluster_config(dir + "/bad.json");
            ADD_FAILURE() << "accepted: " << change.dump();
        } catch (const ConfigError& e) {
            EXPECT_EQ(e.field(), field) << e.what();
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
    };
    refused({{"output", {{"stereo", "quad_buffer"}}}}, "output.stereo", "no quad-buffered");
    refused({{"output", {{"stereo", "side_by_side_half"}, {"width", 481}}}}, "channels[0].id", "even width");
}

// A planet whose centre is on the screen's plane is drawn at the same place for both eyes; 2 m
// behind the screen it has the uncrossed disparity the eyes' geometry predicts, 0.8 m in front the
// crossed one; a side-by-side frame holds the left eye on the left.
TEST(Stereo, APlanetsDisparityIsWhatTheEyesAndTheScreenPredict) {
    test::headless_gl();
    const SceneConfig scene = planet_and_sun(test::scratch_dir("stereo_planet"));
    const ClusterConfig c = wall(StereoMode::SideBySide);
    SceneRenderer r(c, c.channels[0], scene);
    for (const double d : {2.0, 4.0, 1.2}) {
        const Image frame = r.render(planet_at(d));
        ASSERT_EQ(frame.width, 2 * kEye);
        ASSERT_EQ(frame.height, kEye);
        const glm::dvec3 centre(0.0, 0.0, -d);
        const glm::dvec2 left = lit_centre(frame, 0, kEye), right = lit_centre(frame, kEye, kEye);
        const glm::dvec2 want_left = predicted_pixel(-0.5 * kSeparation_m, centre);
        const glm::dvec2 want_right = predicted_pixel(0.5 * kSeparation_m, centre);
        EXPECT_NEAR(right.x - left.x, want_right.x - want_left.x, 0.5) << "disparity at " << d << " m";
        EXPECT_NEAR(left.x, want_left.x, 0.5) << d;
        EXPECT_NEAR(right.y, want_right.y, 0.5) << d;
        if (d == 2.0) EXPECT_NEAR(right.x - left.x, 0.0, 0.5) << "on the screen";
        if (d == 4.0) EXPECT_GT(right.x - left.x, 4.0) << "behind the screen: uncrossed";
        if (d == 1.2) EXPECT_LT(right.x - left.x, -6.0) << "in front of the screen: crossed";
    }
}

// A star is infinitely far: both eyes see it in the same direction. On a wall's screen its two
// images lie the eyes' separation apart (parallel rays); in a channel given by angles (a dome's)
// they are the same pixel.
TEST(Stereo, AStarHasNoParallax) {
    test::headless_gl();
    const SceneConfig scene = planet_and_sun(test::scratch_dir("stereo_star"));
    Snapshot s = planet_at(2.0);
    s.bodies[1].position_m = glm::dvec3(0.0, -1e9, 0.0);  // the planet out of view, behind
    s.settings.star_magnitude_limit = 6.5f;
    const ClusterConfig c = wall(StereoMode::SideBySide);
    SceneRenderer r(c, c.channels[0], scene);
    const Image frame = r.render(s);
    const glm::dvec2 left = lit_centre(frame, 0, kEye, true), right = lit_centre(frame, kEye, kEye, true);
    EXPECT_NEAR(right.x - left.x, kSeparation_m * kEye, 0.5) << "the screen images of parallel rays";
    EXPECT_NEAR(right.y, left.y, 0.1);
    ClusterConfig dome = c;
    dome.channels[0].screen.reset();
    SceneRenderer rd(dome, dome.channels[0], scene);
    const Image df = rd.render(s);
    const glm::dvec2 dl = lit_centre(df, 0, kEye, true), dr = lit_centre(df, kEye, kEye, true);
    EXPECT_NEAR(glm::length(dr - dl), 0.0, 0.1) << "a channel by angles: no disparity";
}

// Each packing holds the eyes that one-eye channels render: side by side, top and bottom at half
// height; the anaglyph is Dubois's matrices of them, pixel by pixel.
TEST(Stereo, PackingsHoldEachEyeAndTheAnaglyphIsItsMatrices) {
    test::headless_gl();
    const SceneConfig scene = planet_and_sun(test::scratch_dir("stereo_packing"));
    const Snapshot s = planet_at(1.5);
    const auto render = [&](StereoMode m, int height) {
        ClusterConfig c = wall(m);
        c.channels[0].height = height;
        SceneRenderer r(c, c.channels[0], scene);
        return r.render(s);
    };
    const Image left = render(StereoMode::Left, kEye), right = render(StereoMode::Right, kEye);
    const Image sbs = render(StereoMode::SideBySide, kEye), ana = render(StereoMode::Anaglyph, kEye);
    const Image half_left = render(StereoMode::Left, kEye / 2), tbh = render(StereoMode::TopBottomHalf, kEye);
    ASSERT_EQ(tbh.height, kEye);
    test::maybe_write_frame("stereo-side-by-side", sbs);
    test::maybe_write_frame("stereo-anaglyph", ana);
    double worst_sbs = 0.0, worst_tb = 0.0, worst_ana = 0.0, peak = 0.0;
    for (int y = 0; y < kEye; ++y)
        for (int x = 0; x < kEye; ++x) {
            const glm::vec3 l(left.pixel(x, y)[0], left.pixel(x, y)[1], left.pixel(x, y)[2]);
            const glm::vec3 r(right.pixel(x, y)[0], right.pixel(x, y)[1], right.pixel(x, y)[2]);
            const glm::vec3 want = shading::dubois_anaglyph(l, r);
            peak = std::max(peak, double(l.g));
            for (int k = 0; k < 3; ++k) {
                worst_sbs = std::max(worst_sbs, double(std::abs(sbs.pixel(x, y)[k] - l[k])));
                worst_sbs = std::max(worst_sbs, double(std::abs(sbs.pixel(x + kEye, y)[k] - r[k])));
                worst_ana = std::max(worst_ana, double(std::abs(ana.pixel(x, y)[k] - want[k])));
                if (y < kEye / 2)  // the left eye on top (row 0 is the top row)
                    worst_tb = std::max(worst_tb, double(std::abs(tbh.pixel(x, y)[k] - half_left.pixel(x, y)[k])));
            }
        }
    ASSERT_GT(peak, 0.0);
    EXPECT_LT(worst_sbs, 1e-6 * peak);
    EXPECT_LT(worst_tb, 1e-6 * peak);
    EXPECT_LT(worst_ana, 1e-5 * peak);
}

// A loopback wall of three screens: the left one side by side, the centre one the right eye alone,
// the right one the left eye alone (an eye per channel). Every channel's frame records the snapshot
// the master sent for it, both eyes of a frame alike; the domemaster is stitched from the left eyes.
TEST(Stereo, ALoopbackWallRendersBothEyesOfAFrameFromOneSnapshot) {
    const std::string dir = test::scratch_dir("stereo_loopback");
    json cfg = json::parse(test::read_text(test::source_path("configs/wall-3screen-stereo.json")));
    for (const char* k : {"scene", "show"}) cfg[k] = test::source_path("configs/" + cfg[k].get<std::string>());
    cfg["output"]["width"] = 48;
    cfg["output"]["height"] = 27;
    cfg["output"]["domemaster_size"] = 96;
    cfg["channels"][1]["stereo"] = "right";
    cfg["channels"][2]["stereo"] = "left";
    const std::string out = test::run_loopback(dir, cfg, 2);
    std::map<uint64_t, std::string> hashes;
    for (const auto& e : test::read_events(out + "/logs/events.jsonl"))
        if (e.is_object() && e.value("event", "") == "frame") hashes[e["frame"].get<uint64_t>()] = e["hash"];
    ASSERT_EQ(hashes.size(), 2u);
    const std::pair<const char*, int> channels[] = {{"wall-left", 96}, {"wall-centre", 48}, {"wall-right", 48}};
    for (const auto& [name, width] : channels)
        for (uint64_t f = 0; f < 2; ++f) {
            FrameMetadata meta;
            const Image im = read_image(out + "/" + name + "/" + frame_file_name(f, "png"), &meta);
            EXPECT_EQ(im.width, width) << name;
            EXPECT_EQ(im.height, 27) << name;
            EXPECT_EQ(meta.snapshot_hash, hashes[f]) << name << " frame " << f;
        }
    EXPECT_TRUE(std::filesystem::exists(out + "/dome/" + frame_file_name(1, "png")));
}

// Integration: the 4-channel loopback renders 10 frames headlessly through real processes,
// real multicast on 127.0.0.1, real EGL and real image files; then the files alone show sync,
// and a star in an overlap lands on the same domemaster pixel from both channels.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "dome/domemaster_stitcher.hpp"
#include "image/frame_image.hpp"
#include "master_node.hpp"
#include "projection/fisheye.hpp"
#include "scene/star_catalog.hpp"
#include "support/cluster_fixture.hpp"
#include "support/loopback_run.hpp"
#include "util/child_process.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;
namespace fs = std::filesystem;

namespace {

constexpr int kFrames = 10;

struct LoopbackRun {
    std::string dir, config, out;
    int exit_code = -1;
};

// One run shared by the checks below (it is the expensive part). ctest runs each TEST in its own
// process, so the checks are one TEST: two runs at once would share ports.
const LoopbackRun& run_once() {
    static LoopbackRun run = [] {
        LoopbackRun r;
        r.dir = test::scratch_dir("loopback4");
        r.config = test::write_test_cluster(r.dir, 47820, 128, 128);
        r.out = r.dir + "/out";
        ChildProcess p({test::bin_path("cupola-loopback"), "--config", r.config, "--frames", std::to_string(kFrames),
                        "--out", r.out, "--timeout", "400"},
                       r.dir + "/loopback.log", {"DISPLAY", "WAYLAND_DISPLAY", "SPDLOG_LEVEL"});
        auto rc = p.wait_for(std::chrono::seconds(420));
        r.exit_code = rc.value_or(-1);
        return r;
    }();
    return run;
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// Luminance-weighted centroid in a (2r+1)^2 window after subtracting the background as a plane
// fitted (least squares) to the window's border: the sky, or a glare, may have a gradient.
std::optional<glm::dvec2> centroid(const Image& img, glm::dvec2 around, int r) {
    int cx = static_cast<int>(std::floor(around.x)), cy = static_cast<int>(std::floor(around.y));
    glm::dmat3 ata(0.0);
    glm::dvec3 atb(0.0);
    for (int y = cy - r; y <= cy + r; ++y)
        for (int x = cx - r; x <= cx + r; ++x) {
            if (x < 0 || y < 0 || x >= img.width || y >= img.height) return std::nullopt;
            if (img.pixel(x, y)[3] <= 0.0f) return std::nullopt;
            if (std::abs(x - cx) != r && std::abs(y - cy) != r) continue;
            const glm::dvec3 row(1.0, x - cx, y - cy);
            ata += glm::outerProduct(row, row);
            atb += row * luminance(img.pixel(x, y));
        }
    const glm::dvec3 plane = glm::inverse(ata) * atb;
    double sw = 0, sx = 0, sy = 0;
    for (int y = cy - r; y <= cy + r; ++y)
        for (int x = cx - r; x <= cx + r; ++x) {
            double w = std::max(0.0, luminance(img.pixel(x, y)) - glm::dot(plane, glm::dvec3(1.0, x - cx, y - cy)));
            sw += w;
            sx += w * (x + 0.5);
            sy += w * (y + 0.5);
        }
    if (sw <= 0) return std::nullopt;
    return glm::dvec2(sx / sw, sy / sw);
}

}  // namespace

void check_every_channel_wrote_every_frame_headless() {
    const auto& r = run_once();
    ASSERT_EQ(r.exit_code, 0) << test::read_text(r.dir + "/loopback.log");
    const ClusterConfig cfg = load_cluster_config(r.config);
    for (const auto& ch : cfg.channels)
        for (int f = 0; f < kFrames; ++f) {
            EXPECT_TRUE(fs::exists(r.out + "/" + ch.name + "/" + frame_file_name(f, "png"))) << ch.name << " " << f;
            EXPECT_TRUE(fs::exists(r.out + "/" + ch.name + "/" + frame_file_name(f, "exr"))) << ch.name << " " << f;
        }
    for (int f = 0; f < kFrames; ++f) EXPECT_TRUE(fs::exists(r.out + "/dome/" + frame_file_name(f, "png"))) << f;
    // Headless: the slaves ran with DISPLAY and WAYLAND_DISPLAY unset, on an EGL platform.
    const std::string log = test::read_text(r.out + "/logs/front.log");
    EXPECT_TRUE(log.find("EGL surfaceless") != std::string::npos || log.find("EGL device") != std::string::npos) << log;
}

void check_same_snapshot_hash_per_frame() {
    const auto& r = run_once();
    ASSERT_EQ(r.exit_code, 0);
    const ClusterConfig cfg = load_cluster_config(r.config);
    const SceneConfig scene = load_scene_config(cfg.scene_file);
    const ShowScript show = ShowScript::load(cfg.show_file, scene);
    // Frame 0 is what the show alone defines (glare sources with their analytic visibility);
    // from frame 1 on the master also writes the cluster's measured glare visibility into the
    // snapshot, so the hash it sent is taken from its events file.
    std::map<int, std::string> sent;
    for (const auto& e : test::read_events(r.out + "/logs/events.jsonl"))
        if (e.value("event", "") == "frame") sent[e.at("frame").get<int>()] = e.at("hash").get<std::string>();
    const AutoExposure exposure(cfg, scene);
    const GlareSources glare(scene, nullptr);
    EXPECT_EQ(sent[0], snapshot_hash(encode_snapshot(make_frame_snapshot(cfg, scene, show, 0, &exposure, &glare))));
    for (int f = 0; f < kFrames; ++f) {
        const std::string expected = sent[f];
        ASSERT_EQ(expected.size(), 16u) << "no hash for frame " << f << " in the master's events";
        for (const auto& ch : cfg.channels) {
            FrameMetadata meta;
            read_image(r.out + "/" + ch.name + "/" + frame_file_name(f, "exr"), &meta);
            EXPECT_EQ(meta.snapshot_hash, expected) << ch.name << " frame " << f;
            EXPECT_EQ(meta.frame, static_cast<uint64_t>(f));
            EXPECT_EQ(meta.channel_id, ch.id);
        }
        FrameMetadata dome;
        read_image(r.out + "/dome/" + frame_file_name(f, "png"), &dome);
        EXPECT_EQ(dome.snapshot_hash, expected);
    }
}

void check_overlap_star_lands_on_one_pixel() {
    const auto& r = run_once();
    ASSERT_EQ(r.exit_code, 0);
    const ClusterConfig cfg = load_cluster_config(r.config);
    const SceneConfig scene = load_scene_config(cfg.scene_file);
    const ShowScript show = ShowScript::load(cfg.show_file, scene);
    const Snapshot snap = make_frame_snapshot(cfg, scene, show, 0);
    // World -> dome frame.
    const glm::dmat3 world_from_dome = glm::mat3_cast(snap.camera_orientation) * dome_tilt_rotation(cfg.dome.tilt_deg);
    const glm::dmat3 dome_from_world = glm::transpose(world_from_dome);
    const int size = cfg.output.domemaster_size;
    const FisheyeMapping fish(cfg.dome.fov_deg);
    std::vector<ChannelFrustum> frusta;
    for (const auto& c : cfg.channels) frusta.push_back(c.frustum());

    const double px_angle = glm::radians(cfg.dome.fov_deg) / size;  // domemaster pixel, radians
    const std::vector<Star> all = load_star_catalog(scene.stars.catalog, scene.stars.magnitude_limit);
    int checked = 0;
    for (const Star& star : load_star_catalog(scene.stars.catalog, 3.5)) {
        const glm::dvec3 d = dome_from_world * star.direction();
        // Isolated stars only: a neighbour within the centroid window would pull the centroid.
        bool crowded = false;
        for (const Star& other : all) {
            const double sep = std::acos(std::clamp(glm::dot(other.direction(), star.direction()), -1.0, 1.0));
            if (sep > 1e-7 && sep < 5.0 * px_angle && other.v_mag < star.v_mag + 2.5f) crowded = true;
        }
        if (crowded) continue;
        // Away from the bodies (the Earth is large in this show).
        bool near_body = false;
        for (const auto& b : snap.bodies) {
            const glm::dvec3 rel = b.position_m - snap.camera_position_m;
            const double ang = std::acos(std::clamp(glm::dot(glm::normalize(rel), star.direction()), -1.0, 1.0));
            if (ang < std::asin(std::min(1.0, scene.bodies[b.id].radius_m / glm::length(rel))) + glm::radians(4.0))
                near_body = true;
        }
        if (near_body) continue;
        for (size_t a = 0; a < frusta.size(); ++a)
            for (size_t b = a + 1; b < frusta.size(); ++b) {
                auto pa = frusta[a].dome_direction_to_pixel(d), pb = frusta[b].dome_direction_to_pixel(d);
                if (!pa || !pb || frusta[a].edge_distance_px(*pa) < 6 || frusta[b].edge_distance_px(*pb) < 6) continue;
                auto uv = fish.direction_to_uv(d);
                if (!uv || glm::length(*uv) > 0.97) continue;
                const glm::dvec2 expected = FisheyeMapping::uv_to_pixel(*uv, size);
                const Image ia = read_image(r.out + "/" + cfg.channels[a].name + "/" + frame_file_name(0, "exr"));
                const Image ib = read_image(r.out + "/" + cfg.channels[b].name + "/" + frame_file_name(0, "exr"));
                const Image fa = remap_channel_to_fisheye(cfg.dome, frusta[a], ia, size);
                const Image fb = remap_channel_to_fisheye(cfg.dome, frusta[b], ib, size);
                auto ca = centroid(fa, expected, 2), cb = centroid(fb, expected, 2);
                ASSERT_TRUE(ca && cb) << "star " << star.name << " not found near " << expected.x << "," << expected.y;
                EXPECT_LE(glm::length(*ca - *cb), 1.0)
                    << star.name << " V=" << star.v_mag << " channels " << cfg.channels[a].name << "/"
                    << cfg.channels[b].name << ": " << ca->x << "," << ca->y << " vs " << cb->x << "," << cb->y;
                EXPECT_LE(glm::length(*ca - expected), 1.0)
                    << star.name << " " << (ca->x - expected.x) << "," << (ca->y - expected.y);
                EXPECT_LE(glm::length(*cb - expected), 1.0)
                    << star.name << " " << (cb->x - expected.x) << "," << (cb->y - expected.y);
                ++checked;
            }
    }
    std::printf("overlap stars checked: %d\n", checked);
    EXPECT_GE(checked, 2) << "too few bright stars in channel overlaps to test";
}

TEST(Loopback4Channel, TenFramesHeadlessInSyncAndSeamless) {
    {
        SCOPED_TRACE("every channel wrote every frame, headless");
        check_every_channel_wrote_every_frame_headless();
    }
    {
        SCOPED_TRACE("all channels carry the same snapshot hash per frame");
        check_same_snapshot_hash_per_frame();
    }
    {
        SCOPED_TRACE("a star in an overlap lands on the same domemaster pixel from both channels");
        check_overlap_star_lands_on_one_pixel();
    }
}

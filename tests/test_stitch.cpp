// Domemaster stitching: registration of overlapping channels, seamless blending, the circle
// mask, and the run-directory sync checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include "config/cluster_config.hpp"
#include "dome/domemaster_stitcher.hpp"
#include "image/frame_image.hpp"
#include "projection/fisheye.hpp"
#include "support/test_support.hpp"

namespace fs = std::filesystem;
using namespace cupola;

namespace {

// Dome-frame direction from azimuth (0 = front -Z, 90 = right +X) and elevation (90 = apex +Y).
glm::dvec3 az_el(double az_deg, double el_deg) {
    const double az = glm::radians(az_deg), el = glm::radians(el_deg);
    return {std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az)};
}

Image make_image(int w, int h, const std::function<void(int, int, float*)>& fill) {
    Image im;
    im.width = w;
    im.height = h;
    im.rgba.assign(static_cast<size_t>(w) * h * 4, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) fill(x, y, im.pixel(x, y));
    return im;
}

// A Gaussian spot (sigma in channel pixels) centred where the channel's own projection puts `dir`.
Image spot_image(const ChannelFrustum& f, const glm::dvec3& dir, double sigma_px) {
    const auto c = f.dome_direction_to_pixel(dir);
    EXPECT_TRUE(c);
    return make_image(f.width(), f.height(), [&](int x, int y, float* p) {
        const double dx = x + 0.5 - c->x, dy = y + 0.5 - c->y;
        const float v = static_cast<float>(std::exp(-(dx * dx + dy * dy) / (2 * sigma_px * sigma_px)));
        p[0] = p[1] = p[2] = v;
        p[3] = 1.0f;
    });
}

// A smooth field on the sphere, sampled at every pixel centre's direction, times a gain.
double field(const glm::dvec3& d) { return 0.5 + 0.3 * d.x + 0.2 * d.y - 0.25 * d.z; }

Image field_image(const ChannelFrustum& f, double gain) {
    return make_image(f.width(), f.height(), [&](int x, int y, float* p) {
        const glm::dvec3 d = f.pixel_to_dome_direction({x + 0.5, y + 0.5});
        const float v = static_cast<float>(gain * field(d));
        p[0] = v;
        p[1] = 0.5f * v;
        p[2] = 0.25f;
        p[3] = 1.0f;
    });
}

struct Centroid {
    double x = 0, y = 0, flux = 0;
};

Centroid centroid(const Image& im) {
    Centroid c;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            const float* p = im.pixel(x, y);
            const double v = p[3] > 0.0f ? p[0] : 0.0;
            c.flux += v;
            c.x += v * (x + 0.5);
            c.y += v * (y + 0.5);
        }
    if (c.flux > 0) c.x /= c.flux, c.y /= c.flux;
    return c;
}

// Largest |difference| between horizontal or vertical neighbours of value(x, y), over pairs of
// pixels that are both covered and both at least `margin_px` (channel pixels) inside some channel.
// The margin keeps out the outer rim of the coverage, where the edges of two channels cross next
// to a hole and every weight is small: the blend there is only as smooth as the hole's edge.
double max_neighbour_step(const Image& im, const std::vector<ChannelFrustum>& channels, double margin_px,
                          const std::function<double(int, int)>& value) {
    const FisheyeMapping fish(180.0);
    std::vector<char> ok(static_cast<size_t>(im.width) * im.height, 0);
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            if (im.pixel(x, y)[3] != 1.0f) continue;
            const auto d = fish.uv_to_direction(FisheyeMapping::pixel_to_uv({x + 0.5, y + 0.5}, im.width));
            double best = -1.0;
            for (const auto& c : channels)
                if (auto p = c.dome_direction_to_pixel(*d)) best = std::max(best, c.edge_distance_px(*p));
            ok[static_cast<size_t>(y) * im.width + x] = best >= margin_px;
        }
    auto good = [&](int x, int y) { return ok[static_cast<size_t>(y) * im.width + x] != 0; };
    double m = 0.0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            if (!good(x, y)) continue;
            if (x + 1 < im.width && good(x + 1, y)) m = std::max(m, std::abs(value(x + 1, y) - value(x, y)));
            if (y + 1 < im.height && good(x, y + 1)) m = std::max(m, std::abs(value(x, y + 1) - value(x, y)));
        }
    return m;
}

const DomeConfig kDome{};  // 180 deg, no tilt
constexpr int kSize = 256;

// Two channels 60 deg apart in yaw, 40 deg half-fov each: they overlap by 20 deg at the horizon.
ChannelFrustum channel_a() { return ChannelFrustum(EulerDeg{0, 30, 0}, FovDeg{40, 40, 40, 40}, 128, 128); }
ChannelFrustum channel_b() { return ChannelFrustum(EulerDeg{60, 30, 0}, FovDeg{40, 40, 40, 40}, 128, 128); }

}  // namespace

TEST(Stitch, SameStarFromTwoChannelsLandsOnTheSameFisheyePixel) {
    const ChannelFrustum a = channel_a(), b = channel_b();
    const glm::dvec3 star = az_el(30.0, 40.0);
    ASSERT_TRUE(a.contains(star));
    ASSERT_TRUE(b.contains(star));
    // The two channels put it at very different places in their own images.
    const glm::dvec2 pa = *a.dome_direction_to_pixel(star), pb = *b.dome_direction_to_pixel(star);
    EXPECT_GT(glm::length(pa - pb), 40.0);
    ASSERT_GT(a.edge_distance_px(pa), 10.0);
    ASSERT_GT(b.edge_distance_px(pb), 10.0);

    const Image ia = spot_image(a, star, 1.5), ib = spot_image(b, star, 1.5);
    const Centroid ca = centroid(remap_channel_to_fisheye(kDome, a, ia, kSize));
    const Centroid cb = centroid(remap_channel_to_fisheye(kDome, b, ib, kSize));
    const glm::dvec2 predicted = FisheyeMapping::uv_to_pixel(*FisheyeMapping(180.0).direction_to_uv(star), kSize);
    ASSERT_GT(ca.flux, 1.0);
    ASSERT_GT(cb.flux, 1.0);
    EXPECT_LT(std::hypot(ca.x - cb.x, ca.y - cb.y), 1.0) << ca.x << "," << ca.y << " vs " << cb.x << "," << cb.y;
    EXPECT_LT(std::hypot(ca.x - predicted.x, ca.y - predicted.y), 1.0) << ca.x << "," << ca.y;
    EXPECT_LT(std::hypot(cb.x - predicted.x, cb.y - predicted.y), 1.0) << cb.x << "," << cb.y;
    // Azimuth 30 deg, elevation 40 deg: right of centre and below it (front is at the bottom).
    EXPECT_GT(predicted.x, kSize / 2.0);
    EXPECT_GT(predicted.y, kSize / 2.0);

    // Stitched together, the star appears once, at the same place, with the flux of one channel.
    const Image s = stitch_domemaster(kDome, {a, b}, {&ia, &ib}, kSize);
    const Centroid cs = centroid(s);
    EXPECT_LT(std::hypot(cs.x - predicted.x, cs.y - predicted.y), 1.0) << cs.x << "," << cs.y;
    EXPECT_NEAR(cs.flux, ca.flux, 0.1 * ca.flux);
}

TEST(Stitch, StarSeenByOneChannelOnlyIsWhereTheFisheyePredicts) {
    const ChannelFrustum a = channel_a();
    const glm::dvec3 star = az_el(-20.0, 55.0);
    ASSERT_TRUE(a.contains(star));
    const Centroid c = centroid(remap_channel_to_fisheye(kDome, a, spot_image(a, star, 1.5), kSize));
    const glm::dvec2 predicted = FisheyeMapping::uv_to_pixel(*FisheyeMapping(180.0).direction_to_uv(star), kSize);
    EXPECT_LT(std::hypot(c.x - predicted.x, c.y - predicted.y), 1.0) << c.x << "," << c.y;
    EXPECT_LT(predicted.x, kSize / 2.0);  // left of centre
}

TEST(Stitch, IdenticallySampledSmoothFieldStitchesToTheField) {
    const ChannelFrustum a = channel_a(), b = channel_b();
    const Image ia = field_image(a, 1.0), ib = field_image(b, 1.0);
    const Image s = stitch_domemaster(kDome, {a, b}, {&ia, &ib}, kSize);
    const FisheyeMapping fish(180.0);
    double max_err = 0.0;
    int covered = 0, overlap = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const auto d = fish.uv_to_direction(FisheyeMapping::pixel_to_uv({x + 0.5, y + 0.5}, kSize));
            const float* p = s.pixel(x, y);
            const bool ina = d && a.contains(*d), inb = d && b.contains(*d);
            EXPECT_EQ(p[3], (ina || inb) ? 1.0f : 0.0f) << x << "," << y;
            if (!(ina || inb)) {
                EXPECT_EQ(p[0], 0.0f);
                continue;
            }
            ++covered;
            overlap += ina && inb;
            max_err = std::max(max_err, std::abs(p[0] - field(*d)));
            max_err = std::max(max_err, std::abs(p[2] - 0.25));
        }
    EXPECT_GT(covered, 5000);
    EXPECT_GT(overlap, 500);
    EXPECT_LT(max_err, 0.005);
}

TEST(Stitch, FeatheredOverlapHasNoSeam) {
    // Channel B is 20% brighter than A (a mismatched projector). A hard switch between channels
    // shows that as a step; the feathered blend must spread it out.
    const ChannelFrustum a = channel_a(), b = channel_b();
    const Image ia = field_image(a, 1.0), ib = field_image(b, 1.2);
    const FisheyeMapping fish(180.0);
    // The stitched value divided by the field leaves the blend of the gains (1 .. 1.2).
    auto gain_of = [&](const Image& s) {
        return [&s, &fish](int x, int y) {
            const auto d = fish.uv_to_direction(FisheyeMapping::pixel_to_uv({x + 0.5, y + 0.5}, s.width));
            return s.pixel(x, y)[0] / field(*d);
        };
    };
    const Image feathered = stitch_domemaster(kDome, {a, b}, {&ia, &ib}, kSize, 8.0);
    const Image hard = stitch_domemaster(kDome, {a, b}, {&ia, &ib}, kSize, 0.0);
    const std::vector<ChannelFrustum> both = {a, b};
    const double step_feathered = max_neighbour_step(feathered, both, 8.0, gain_of(feathered));
    const double step_hard = max_neighbour_step(hard, both, 8.0, gain_of(hard));
    // A hard switch from A alone to the 50/50 average steps the gain by 0.1; a seam-free blend
    // changes it gradually (the smoothstep over 8 channel pixels: ~0.2 * 0.2 per fisheye pixel).
    EXPECT_GT(step_hard, 0.09);  // the metric does see a seam
    EXPECT_LT(step_feathered, 0.05);
    // Raw neighbour differences too: the feathered stitch is much smoother than the hard one and
    // close to the field's own gradient.
    const double step_field = max_neighbour_step(feathered, both, 8.0, [&](int x, int y) {
        const auto d = fish.uv_to_direction(FisheyeMapping::pixel_to_uv({x + 0.5, y + 0.5}, kSize));
        return field(*d);
    });
    const double raw_feathered =
        max_neighbour_step(feathered, both, 8.0, [&](int x, int y) { return feathered.pixel(x, y)[0]; });
    const double raw_hard = max_neighbour_step(hard, both, 8.0, [&](int x, int y) { return hard.pixel(x, y)[0]; });
    // (Measured: field 0.0045, feathered 0.030, hard 0.094.)
    EXPECT_LT(raw_feathered, 0.5 * raw_hard) << raw_feathered << " vs " << raw_hard;
    EXPECT_LT(raw_feathered, step_field + 0.04) << raw_feathered << " vs " << step_field;
    // Far from any edge each channel is shown as it is: the gain is 1 in A only, 1.2 in B only.
    const auto fa = FisheyeMapping::uv_to_pixel(*fish.direction_to_uv(az_el(-20, 30)), kSize);
    const auto fb = FisheyeMapping::uv_to_pixel(*fish.direction_to_uv(az_el(80, 30)), kSize);
    EXPECT_NEAR(gain_of(feathered)(int(fa.x), int(fa.y)), 1.0, 0.01);
    EXPECT_NEAR(gain_of(feathered)(int(fb.x), int(fb.y)), 1.2, 0.01);
}

TEST(Stitch, CircleMaskAndFullCoverage) {
    // Four walls and a cap cover the whole hemisphere.
    std::vector<ChannelFrustum> rig;
    for (double yaw : {0.0, 90.0, 180.0, 270.0}) rig.emplace_back(EulerDeg{yaw, 20, 0}, FovDeg{50, 50, 45, 25}, 64, 64);
    rig.emplace_back(EulerDeg{0, 90, 0}, FovDeg{50, 50, 50, 50}, 64, 64);
    std::vector<Image> images;
    std::vector<const Image*> ptrs;
    for (const auto& f : rig) images.push_back(field_image(f, 1.0));
    for (const auto& im : images) ptrs.push_back(&im);
    const int size = 128;
    const Image s = stitch_domemaster(kDome, rig, ptrs, size);
    const FisheyeMapping fish(180.0);
    int inside = 0, outside = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::dvec2 uv = FisheyeMapping::pixel_to_uv({x + 0.5, y + 0.5}, size);
            const float* p = s.pixel(x, y);
            if (glm::length(uv) > 1.0) {
                ++outside;
                EXPECT_EQ(p[3], 0.0f) << x << "," << y;
                EXPECT_EQ(p[0], 0.0f);
                EXPECT_EQ(p[1], 0.0f);
                EXPECT_EQ(p[2], 0.0f);
            } else {
                ++inside;
                EXPECT_EQ(p[3], 1.0f) << x << "," << y;
                EXPECT_NEAR(p[0], field(*fish.uv_to_direction(uv)), 0.01) << x << "," << y;
            }
        }
    // pi/4 of the square is inside the circle.
    EXPECT_NEAR(static_cast<double>(inside) / (size * size), M_PI / 4, 0.01);
    EXPECT_GT(outside, 0);
    // The corners are always outside.
    EXPECT_EQ(s.pixel(0, 0)[3], 0.0f);
    EXPECT_EQ(s.pixel(size - 1, size - 1)[3], 0.0f);
}

TEST(Stitch, BadArgumentsThrow) {
    const ChannelFrustum a = channel_a();
    const Image ia = field_image(a, 1.0);
    const Image wrong = make_image(10, 10, [](int, int, float*) {});
    EXPECT_THROW(stitch_domemaster(kDome, {a}, {&ia, &ia}, 64), std::invalid_argument);
    EXPECT_THROW(stitch_domemaster(kDome, {a}, {&wrong}, 64), std::invalid_argument);
    EXPECT_THROW(stitch_domemaster(kDome, {a}, {&ia}, 0), std::invalid_argument);
    EXPECT_THROW(remap_channel_to_fisheye(kDome, a, wrong, 64), std::invalid_argument);
}

namespace {

ClusterConfig two_channel_config(const std::string& dir) {
    ClusterConfig cfg;
    cfg.file = dir + "/cluster.json";
    cfg.directory = dir;
    cfg.output.formats = {"png", "exr"};
    cfg.output.domemaster_size = 96;
    cfg.output.exposure = 1.0;
    ChannelConfig a;
    a.id = 0;
    a.name = "A";
    a.orientation = EulerDeg{0, 30, 0};
    a.fov = FovDeg{40, 40, 40, 40};
    a.width = a.height = 64;
    ChannelConfig b = a;
    b.id = 1;
    b.name = "B";
    b.orientation = EulerDeg{60, 30, 0};
    cfg.channels = {a, b};
    return cfg;
}

FrameMetadata meta_for(const ChannelConfig& ch, uint64_t frame, const std::string& hash) {
    FrameMetadata m;
    m.channel_id = ch.id;
    m.channel_name = ch.name;
    m.frame = frame;
    m.sim_time_s = 1000.0 + frame / 30.0;
    m.snapshot_hash = hash;
    m.renderer = "test";
    return m;
}

bool any_problem_has(const StitchReport& r, const std::vector<std::string>& words) {
    for (const auto& p : r.problems) {
        bool all = true;
        for (const auto& w : words) all = all && p.find(w) != std::string::npos;
        if (all) return true;
    }
    return false;
}

}  // namespace

TEST(Stitch, RunDirectoryReportsDisagreeingHashesAndMissingFrames) {
    const std::string root = test::scratch_dir("stitch_run_directory");
    const std::string in = root + "/run", out = root + "/dome";
    const ClusterConfig cfg = two_channel_config(root);
    const ChannelConfig &ca = cfg.channels[0], &cb = cfg.channels[1];
    const Image ia = field_image(ca.frustum(), 1.0), ib = field_image(cb.frustum(), 1.0);
    // Channel frames are written with exposure 0.5: the stitcher must undo it (EXR and PNG alike).
    // Frame 1: in sync. Frame 2: B rendered another snapshot. Frame 3: B has no file.
    write_frame(in + "/A", ia, meta_for(ca, 1, "00000000000000a1"), {"exr"}, 0.5);
    write_frame(in + "/B", ib, meta_for(cb, 1, "00000000000000a1"), {"png"}, 0.5);
    write_frame(in + "/A", ia, meta_for(ca, 2, "00000000000000a2"), {"exr"}, 2.0);
    write_frame(in + "/B", ib, meta_for(cb, 2, "00000000000000ff"), {"exr", "png"}, 2.0);
    write_frame(in + "/A", ia, meta_for(ca, 3, "00000000000000a3"), {"exr"}, 2.0);
    test::write_text(in + "/A/readme.txt", "not a frame");

    const StitchReport r = stitch_run_directory(cfg, in, out, std::nullopt, 0);
    EXPECT_EQ(r.frames, (std::vector<uint64_t>{1, 2, 3}));
    EXPECT_TRUE(any_problem_has(r, {"frame 2", "hash", "00000000000000a2", "00000000000000ff"}));
    EXPECT_TRUE(any_problem_has(r, {"frame 3", "missing", "B"}));
    for (const auto& p : r.problems) EXPECT_EQ(p.find("frame 1:"), std::string::npos) << p;
    EXPECT_EQ(r.problems.size(), 2u);
    EXPECT_EQ(r.written.size(), 6u);
    for (uint64_t f : {1, 2, 3})
        for (const char* ext : {"png", "exr"}) EXPECT_TRUE(fs::exists(fs::path(out) / frame_file_name(f, ext)));

    // The domemaster's metadata and content.
    FrameMetadata m;
    const Image dome = read_image_radiance(out + "/" + frame_file_name(1, "exr"), &m);
    EXPECT_EQ(m.channel_id, -1);
    EXPECT_EQ(m.channel_name, "dome");
    EXPECT_EQ(m.frame, 1u);
    EXPECT_EQ(m.snapshot_hash, "00000000000000a1");
    EXPECT_EQ(m.sim_time_s, 1000.0 + 1 / 30.0);
    // The domemaster keeps the frame's own exposure (auto exposure changes it per frame).
    EXPECT_EQ(m.exposure, 0.5);
    FrameMetadata m2;
    read_image(out + "/" + frame_file_name(2, "exr"), &m2);
    EXPECT_EQ(m2.exposure, 2.0);
    ASSERT_EQ(dome.width, 96);
    ASSERT_EQ(dome.height, 96);
    const Image expected = stitch_domemaster(cfg.dome, {ca.frustum(), cb.frustum()}, {&ia, &ib}, 96);
    double max_err = 0.0;
    for (size_t i = 0; i < dome.rgba.size(); ++i)
        max_err = std::max(max_err, double(std::abs(dome.rgba[i] - expected.rgba[i])));
    // B went through 8-bit sRGB: about one 1/255 step at most (exposure 0.5 undone).
    EXPECT_LT(max_err, 0.015);
    // Frame 3 is A alone: B's part of the dome is empty (alpha 0), A's part is there.
    const Image dome3 = read_image(out + "/" + frame_file_name(3, "exr"));
    const auto pa = FisheyeMapping::uv_to_pixel(*FisheyeMapping().direction_to_uv(az_el(-20, 40)), 96);
    const auto pb = FisheyeMapping::uv_to_pixel(*FisheyeMapping().direction_to_uv(az_el(80, 40)), 96);
    EXPECT_EQ(dome3.pixel(int(pa.x), int(pa.y))[3], 1.0f);
    EXPECT_EQ(dome3.pixel(int(pb.x), int(pb.y))[3], 0.0f);

    // One frame only.
    const StitchReport r1 = stitch_run_directory(cfg, in, root + "/one", 1, 64);
    EXPECT_EQ(r1.frames, (std::vector<uint64_t>{1}));
    EXPECT_TRUE(r1.problems.empty());
    ASSERT_EQ(r1.written.size(), 2u);
    EXPECT_EQ(read_image(r1.written[0]).width, 64);

    // A frame nobody rendered.
    const StitchReport r9 = stitch_run_directory(cfg, in, root + "/none", 9, 0);
    EXPECT_TRUE(r9.frames.empty());
    EXPECT_TRUE(r9.written.empty());
    EXPECT_TRUE(any_problem_has(r9, {"frame 9"}));
}

TEST(Stitch, RunDirectoryWithoutChannelFolders) {
    const std::string root = test::scratch_dir("stitch_empty_run");
    const ClusterConfig cfg = two_channel_config(root);
    const StitchReport r = stitch_run_directory(cfg, root, root + "/out", std::nullopt, 0);
    EXPECT_TRUE(r.frames.empty());
    EXPECT_FALSE(r.problems.empty());
    EXPECT_TRUE(any_problem_has(r, {"channel A"}));
    const StitchReport r2 = stitch_run_directory(cfg, root + "/does-not-exist", root + "/out", std::nullopt, 0);
    EXPECT_TRUE(any_problem_has(r2, {"does-not-exist"}));
}

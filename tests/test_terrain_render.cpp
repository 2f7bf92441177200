// The terrain drawn (slave/passes/terrain_drawer.cpp, shaders/terrain.vert/.frag), on a real
// headless EGL context (llvmpipe on CI): the Earth of the earth-moon scene as procedural relief, or
// as a GeoTIFF the test writes. No background shows through the relief at any level change, two
// narrow channels draw what one wide channel draws, every channel of a dome draws the same cut,
// the relief shows at sunset where the smooth sphere is flat, a cone in a file is drawn where it
// lies, the render loop never waits for a tile, and a camera 1 m above the ground 1 AU from the
// origin draws what it draws at the origin.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "glare/glare_sources.hpp"
#include "image/frame_image.hpp"
#include "passes/terrain_drawer.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "support/earth_moon_scene.hpp"
#include "support/geotiff_writer.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"
#include "terrain/body_relief.hpp"
#include "terrain/cube_sphere.hpp"
#include "terrain/terrain_clearance.hpp"

using namespace cupola;

namespace {

constexpr double kDeg = 0.017453292519943295769;
constexpr double kAu_m = 1.495978707e11;

EglContext& context() { return test::headless_gl("TerrainRender"); }

// The earth-moon scene with the Earth's surface as relief.
SceneConfig terrain_scene(const std::string& elevation = "") {
    SceneConfig sc = test::earth_moon_scene();
    BodyConfig& earth = sc.bodies[sc.find("earth")->id];
    earth.terrain.present = true;
    earth.terrain.procedural_wavelength_m = 40e3;
    earth.terrain.procedural_amplitude_m = 3000.0;
    earth.terrain.seed = 7;
    earth.terrain.elevation = elevation;
    return sc;
}

// The cone of these tests: 2000 m high at (lon 10.25, lat 45.5 geodetic), 0.5 degrees in radius.
double cone_height_m(double lon, double lat) {
    return std::max(0.0, 2000.0 * (1.0 - std::hypot(lon - 10.25, lat - 45.5) / 0.5));
}

// The Earth as that cone alone (a GeoTIFF of 0.01 degree samples, no procedural relief) and without
// air: the Sun's light alone, so a shadow is black.
SceneConfig lone_cone_scene(const std::string& tag) {
    const std::string dir = test::scratch_dir(tag);
    SceneConfig sc = terrain_scene(test::write_geotiff(dir + "/cone.tif", 150, 100, 9.5, 46.0, 0.01, cone_height_m));
    BodyConfig& earth = sc.bodies[sc.find("earth")->id];
    earth.terrain.procedural_amplitude_m = 0.0;
    earth.atmosphere.present = false;
    return sc;
}

ChannelConfig channel(const std::string& name, FovDeg fov, int w, int h, EulerDeg orientation = {}) {
    ChannelConfig ch;
    ch.name = name;
    ch.fov = fov;
    ch.width = w;
    ch.height = h;
    ch.orientation = orientation;
    return ch;
}

ClusterConfig cluster_of(std::vector<ChannelConfig> channels) {
    ClusterConfig c;
    c.channels = std::move(channels);
    return c;
}

// A world position over the Earth (at `earth_m`, unrotated) at planetocentric (lat, lon) and
// radius r; the local east, north and up there.
struct Place {
    glm::dvec3 up, east, north;
};
Place place(double lat_deg, double lon_deg) {
    Place p;
    p.up = terrain::lat_lon_to_direction(lat_deg * kDeg, lon_deg * kDeg);
    p.east = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), p.up));
    p.north = glm::cross(p.up, p.east);
    return p;
}

// The camera at `camera_m` looking along `forward` with `up_hint` up; the Sun toward sun_dir, 1 AU
// from the Earth at earth_m; the Moon far to the side.
Snapshot snapshot(const SceneConfig& sc, const glm::dvec3& earth_m, const glm::dvec3& camera_m,
                  const glm::dvec3& forward, const glm::dvec3& up_hint, const glm::dvec3& sun_dir) {
    Snapshot s;
    s.bodies.resize(sc.bodies.size());
    for (auto& b : s.bodies) b.id = static_cast<uint16_t>(&b - s.bodies.data());
    s.bodies[sc.find("earth")->id].position_m = earth_m;
    s.bodies[sc.find("sun")->id].position_m = earth_m + kAu_m * glm::normalize(sun_dir);
    s.bodies[sc.find("moon")->id].position_m = earth_m + 3.844e8 * glm::normalize(glm::cross(sun_dir, up_hint));
    s.camera_position_m = camera_m;
    const glm::dvec3 f = glm::normalize(forward), right = glm::normalize(glm::cross(f, up_hint));
    s.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(right, f), -f));
    return s;
}

uint16_t earth_id(const SceneConfig& sc) { return sc.find("earth")->id; }

// A camera height_m above the relief at a place (the relief's own height there added).
glm::dvec3 above_ground(const SceneConfig& sc, const Place& p, double height_m) {
    const terrain::TerrainClearance ground(sc);
    BodyState earth;
    earth.id = earth_id(sc);
    const double radius = sc.find("earth")->radius_m;
    return p.up * (radius + ground.ground_height_m(earth, p.up * radius) + height_m);
}

// Renders once (the tiles are queued), waits until every tile is built, renders again.
Image render_settled(SceneRenderer& r, const Snapshot& s) {
    r.render(s);
    r.terrain().wait_idle();
    return r.render(s);
}

// The world direction of pixel (x, y) (row 0 at the top) of a channel facing the camera's view.
glm::dvec3 pixel_ray(const ChannelConfig& ch, const Snapshot& s, int x, int y) {
    const ChannelFrustum f = ch.frustum();
    const glm::vec4 t(f.tan_left(), f.tan_right(), f.tan_down(), f.tan_up());
    const glm::vec3 v =
        shading::channel_ray(glm::vec2(x + 0.5f, ch.height - y - 0.5f), glm::vec2(ch.width, ch.height), t);
    return glm::mat3_cast(s.camera_orientation) * channel_rotation(ch.orientation) * glm::dvec3(v);
}

// Whether the ray meets a sphere of radius r about the centre.
bool ray_meets_sphere(const glm::dvec3& from, const glm::dvec3& dir, const glm::dvec3& centre, double r) {
    const glm::dvec3 oc = from - centre;
    const double b = glm::dot(oc, dir), c = glm::dot(oc, oc) - r * r;
    return b * b - c >= 0.0 && (b < 0.0 || c < 0.0);
}

// Pixels inside the silhouette of the relief's lowest sphere: (counted, showing no geometry).
std::pair<int, int> holes_in_silhouette(const Image& geometry, const ChannelConfig& ch, const Snapshot& s,
                                        double lowest_r_m) {
    int inside = 0, holes = 0;
    for (int y = 0; y < geometry.height; ++y)
        for (int x = 0; x < geometry.width; ++x) {
            if (!ray_meets_sphere(s.camera_position_m, pixel_ray(ch, s, x, y), glm::dvec3(0.0), lowest_r_m)) continue;
            ++inside;
            if (geometry.rgba[4 * (static_cast<size_t>(y) * geometry.width + x) + 3] < 0.0f) ++holes;
        }
    return {inside, holes};
}

double luminance(const Image& img, int x, int y) {
    const float* p = &img.rgba[4 * (static_cast<size_t>(y) * img.width + x)];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

double lower_half_luminance_std(const Image& img) {
    double sum = 0.0, sq = 0.0;
    int n = 0;
    for (int y = img.height / 2; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double l = luminance(img, x, y);
            sum += l;
            sq += l * l;
            ++n;
        }
    const double mean = sum / n;
    return std::sqrt(std::max(sq / n - mean * mean, 0.0));
}

}  // namespace

TEST(TerrainRender, NoBackgroundInsideThePlanetsSilhouetteAcrossLevelChanges) {
    context();
    const SceneConfig sc = terrain_scene();
    const ChannelConfig ch = channel("view", FovDeg{40, 40, 30, 30}, 96, 72);
    const ClusterConfig cl = cluster_of({ch});
    const double radius = sc.find("earth")->radius_m;
    const double lowest = radius + terrain::open_body_relief(*sc.find("earth")).relief->min_height_m();
    SceneRenderer r(cl, ch, sc);
    const Place p = place(30.0, 20.0);
    // Down from 300 km to 300 m, looking 35 degrees down toward the horizon: every step changes
    // the levels of the cut; the first frame at each height draws stand-ins next to built tiles.
    int inside_total = 0;
    for (double height : {300e3, 60e3, 12e3, 2.5e3, 300.0}) {
        const glm::dvec3 forward = glm::normalize(p.north - 0.7 * p.up);
        const Snapshot s = snapshot(sc, glm::dvec3(0.0), above_ground(sc, p, height), forward, p.up, p.up + p.east);
        r.render(s);
        const auto [inside_first, holes_first] = holes_in_silhouette(r.read_geometry(), ch, s, lowest);
        EXPECT_EQ(holes_first, 0) << "at " << height << " m, while tiles load ("
                                  << r.terrain().last_frame(earth_id(sc)).stand_ins << " stand-ins)";
        render_settled(r, s);
        const auto [inside, holes] = holes_in_silhouette(r.read_geometry(), ch, s, lowest);
        EXPECT_EQ(holes, 0) << "at " << height << " m";
        EXPECT_EQ(r.terrain().last_frame(earth_id(sc)).stand_ins, 0);
        inside_total += inside + inside_first;
    }
    EXPECT_GT(inside_total, 10 * 96 * 72 / 2)
        << "the planet must fill much of the frames for the test to mean anything";
}

TEST(TerrainRender, TwoNarrowChannelsEqualOneWideAtEveryStepOfADescent) {
    context();
    const SceneConfig sc = terrain_scene();
    const ChannelConfig wide = channel("wide", FovDeg{40, 40, 20, 20}, 96, 36);
    const ChannelConfig left = channel("left", FovDeg{40, 0, 20, 20}, 48, 36);
    const ChannelConfig right = channel("right", FovDeg{0, 40, 20, 20}, 48, 36);
    const ClusterConfig one = cluster_of({wide}), two = cluster_of({left, right});
    SceneRenderer rw(one, wide, sc), rl(two, left, sc), rr(two, right, sc);
    const double radius = sc.find("earth")->radius_m;
    const Place p = place(-12.0, 140.0);
    for (double height : {150e3, 20e3, 5e3}) {
        const glm::dvec3 forward = glm::normalize(p.east - 0.4 * p.up);
        const Snapshot s = snapshot(sc, glm::dvec3(0.0), above_ground(sc, p, height), forward, p.up, p.up + p.north);
        const Image w = render_settled(rw, s), l = render_settled(rl, s), rt = render_settled(rr, s);
        // The two narrow nodes choose one cut. (The wide cluster's may differ outside the view:
        // each channel's frustum test is conservative near its corners.)
        EXPECT_EQ(rl.terrain().last_frame(earth_id(sc)).cut_hash, rr.terrain().last_frame(earth_id(sc)).cut_hash)
            << height;
        double worst = 0.0, sum = 0.0, peak = 0.0;
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x) {
                const double a = luminance(w, x, y), b = x < 48 ? luminance(l, x, y) : luminance(rt, x - 48, y);
                worst = std::max(worst, std::abs(a - b));
                sum += std::abs(a - b);
                peak = std::max(peak, a);
            }
        ASSERT_GT(peak, 0.0);
        // Float noise: the two projections round the same vertices differently.
        EXPECT_LE(worst, 1e-3 * peak) << "at " << height << " m";
        EXPECT_LE(sum / (w.width * w.height), 1e-5 * peak) << "at " << height << " m";
        std::printf("at %.0f m: worst %.2e, mean %.2e of the peak\n", height, worst / peak,
                    sum / (w.width * w.height) / peak);
    }
}

TEST(TerrainRender, EveryChannelOfADomeDrawsTheSameCut) {
    context();
    const SceneConfig sc = terrain_scene();
    std::vector<ChannelConfig> chs;
    for (int k = 0; k < 4; ++k)
        chs.push_back(channel("c" + std::to_string(k), FovDeg{46, 46, 46, 46}, 40, 40, EulerDeg{90.0 * k, 20.0, 0.0}));
    const ClusterConfig dome = cluster_of(chs);
    const double radius = sc.find("earth")->radius_m;
    const Place p = place(46.0, 7.7);
    const Snapshot s = snapshot(sc, glm::dvec3(0.0), above_ground(sc, p, 1500.0), p.north, p.up, p.up - p.east);
    std::vector<uint64_t> hashes;
    size_t tiles = 0;
    for (const ChannelConfig& ch : chs) {
        SceneRenderer r(dome, ch, sc);
        render_settled(r, s);
        hashes.push_back(r.terrain().last_frame(earth_id(sc)).cut_hash);
        tiles = r.terrain().last_frame(earth_id(sc)).cut_tiles;
    }
    EXPECT_GT(tiles, 20u);
    for (uint64_t h : hashes) EXPECT_EQ(h, hashes[0]);
}

TEST(TerrainRender, AtSunsetTheReliefVariesTheGroundsLuminanceFiveTimesMoreThanTheSphere) {
    context();
    SceneConfig relief = terrain_scene();
    SceneConfig smooth = test::earth_moon_scene();
    const ChannelConfig ch = channel("sunset", FovDeg{40, 40, 25, 25}, 96, 60);
    const ClusterConfig cl = cluster_of({ch});
    const double radius = relief.find("earth")->radius_m;
    const Place p = place(46.0, 7.7);
    // 1.5 km above the ground, the Sun 4 degrees over the western horizon, looking west and a little down.
    const glm::dvec3 west = -p.east;
    const glm::dvec3 sun = glm::normalize(west + std::tan(4.0 * kDeg) * p.up);
    const Snapshot s = snapshot(relief, glm::dvec3(0.0), above_ground(relief, p, 1500.0),
                                glm::normalize(p.north + 0.3 * west - 0.3 * p.up), p.up, sun);
    SceneRenderer with(cl, ch, relief), without(cl, ch, smooth);
    const Image a = render_settled(with, s), b = without.render(s);
    const double sa = lower_half_luminance_std(a), sb = lower_half_luminance_std(b);
    const TerrainFrameStats& st = with.terrain().last_frame(earth_id(relief));
    std::printf("cut %zu tiles, drawn %zu, %zu triangles\n", st.cut_tiles, st.drawn_tiles, st.triangles);
    if (const char* dir = std::getenv("CUPOLA_TERRAIN_IMAGES")) {
        write_frame(std::string(dir) + "/relief", a, FrameMetadata{}, {"exr"}, 1.0);
        write_frame(std::string(dir) + "/sphere", b, FrameMetadata{}, {"exr"}, 1.0);
        write_frame(std::string(dir) + "/relief_geometry", with.read_geometry(), FrameMetadata{}, {"exr"}, 1.0);
    }
    EXPECT_GT(sa, 5.0 * sb) << "relief " << sa << ", sphere " << sb;
    std::printf("lower half luminance std: relief %.3g, sphere %.3g (%.1fx)\n", sa, sb, sa / sb);
    EXPECT_GT(sa, 0.0);
}

TEST(TerrainRender, AConeInAGeoTiffIsDrawnAtItsLatitudeAndLongitudeWithinOneSample) {
    context();
    const std::string dir = test::scratch_dir("terrain_render_cone");
    const double step = 0.01;  // degrees
    // A cone 2000 m high at (lon 10.25, lat 45.5 geodetic), 0.5 degrees across its base.
    const std::string file = test::write_geotiff(dir + "/cone.tif", 150, 100, 9.5, 46.0, step, cone_height_m);
    SceneConfig sc = terrain_scene(file);
    sc.bodies[sc.find("earth")->id].terrain.procedural_amplitude_m = 0.0;  // the cone alone
    const ChannelConfig ch = channel("down", FovDeg{15, 15, 15, 15}, 128, 128);
    const ClusterConfig cl = cluster_of({ch});
    const double radius = sc.find("earth")->radius_m, lat = test::centric_deg(45.5);
    // 40 km up, 0.04 degrees off the peak to the south-west, looking straight down.
    const Place p = place(lat - 0.04, 10.25 - 0.04);
    const Snapshot s = snapshot(sc, glm::dvec3(0.0), p.up * (radius + 40e3), -p.up, p.north, p.up + p.east);
    SceneRenderer r(cl, ch, sc);
    render_settled(r, s);
    const Image g = r.read_geometry();
    double best = -1e30;
    glm::dvec2 best_lat_lon(0.0);
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const float d = g.rgba[4 * (static_cast<size_t>(y) * g.width + x) + 3];
            if (d < 0.0f) continue;
            const glm::dvec3 hit = s.camera_position_m + static_cast<double>(d) * pixel_ray(ch, s, x, y);
            const double h = glm::length(hit) - radius;
            if (h > best) best = h, best_lat_lon = terrain::direction_to_lat_lon_rad(glm::normalize(hit)) / kDeg;
        }
    EXPECT_NEAR(best, 2000.0, 100.0);
    EXPECT_NEAR(best_lat_lon.x, lat, step);
    EXPECT_NEAR(best_lat_lon.y, 10.25, step);
}

TEST(TerrainRender, ACorruptElevationFileFallsBackToProceduralReliefNamingIt) {
    const std::string dir = test::scratch_dir("terrain_render_corrupt");
    const std::string file = dir + "/broken.tif";
    test::write_text(file, "II*\0 this is not a GeoTIFF");
    SceneConfig sc = terrain_scene(file);
    const terrain::BodyRelief r = terrain::open_body_relief(*sc.find("earth"));
    EXPECT_NE(r.fallback.find(file), std::string::npos) << r.fallback;
    EXPECT_NE(r.fallback.find("procedural"), std::string::npos) << r.fallback;
    ASSERT_TRUE(r.relief);
    EXPECT_FALSE(r.relief->has_data());
    EXPECT_GT(r.relief->max_height_m(), 100.0);  // the procedural relief is there
    // And the renderer comes up with it.
    context();
    const ChannelConfig ch = channel("view", FovDeg{30, 30, 30, 30}, 16, 16);
    SceneRenderer renderer(cluster_of({ch}), ch, sc);
    EXPECT_TRUE(renderer.terrain().has_terrain(earth_id(sc)));
}

TEST(TerrainRender, TheRenderLoopNeverWaitsForATile) {
    context();
    const SceneConfig sc = terrain_scene();
    const ChannelConfig ch = channel("view", FovDeg{40, 40, 30, 30}, 32, 24);
    const ClusterConfig cl = cluster_of({ch});
    SceneRenderer r(cl, ch, sc);
    std::mutex m;
    std::condition_variable cv;
    bool open = false;
    std::atomic<int> held{0};
    r.terrain().set_build_hook([&](const terrain::TileKey&) {
        ++held;
        std::unique_lock<std::mutex> lock(m);
        cv.wait(lock, [&] { return open; });
    });
    const double radius = sc.find("earth")->radius_m;
    const Place p = place(10.0, -60.0);
    const Snapshot s =
        snapshot(sc, glm::dvec3(0.0), above_ground(sc, p, 2000.0), glm::normalize(p.north - 0.3 * p.up), p.up, p.up);
    for (int k = 0; k < 3; ++k) r.render(s);  // returns with every build held at the gate
    EXPECT_GT(held.load(), 0);
    EXPECT_GT(r.terrain().last_frame(earth_id(sc)).stand_ins, 0);
    EXPECT_EQ(r.terrain().store_stats(earth_id(sc)).fallback_frames, 3u);
    {
        std::lock_guard<std::mutex> lock(m);
        open = true;
    }
    cv.notify_all();
    render_settled(r, s);
    EXPECT_EQ(r.terrain().last_frame(earth_id(sc)).stand_ins, 0);
}

TEST(TerrainRender, OneMetreAboveTheGroundAtOneAuItDrawsWhatItDrawsAtTheOrigin) {
    context();
    const SceneConfig sc = terrain_scene();
    const ChannelConfig ch = channel("view", FovDeg{40, 40, 30, 30}, 64, 48);
    const ClusterConfig cl = cluster_of({ch});
    const double radius = sc.find("earth")->radius_m;
    const Place p = place(-33.0, 18.0);
    const glm::dvec3 offset = above_ground(sc, p, 1.0);
    const glm::dvec3 forward = glm::normalize(p.north - 0.2 * p.up);
    const glm::dvec3 far_away(kAu_m, 0.3 * kAu_m, 0.0);
    const Snapshot at_origin = snapshot(sc, glm::dvec3(0.0), offset, forward, p.up, p.up + p.east);
    const Snapshot at_1au = snapshot(sc, far_away, far_away + offset, forward, p.up, p.up + p.east);
    SceneRenderer a(cl, ch, sc), b(cl, ch, sc);
    render_settled(a, at_origin);
    render_settled(b, at_1au);
    const Image ga = a.read_geometry(), gb = b.read_geometry();
    // The distance of every pixel's ground agrees within what 0.1 px of motion would change.
    const double pixel_rad = 80.0 * kDeg / 64;
    int compared = 0, off = 0;
    for (size_t i = 3; i < ga.rgba.size(); i += 4) {
        const double da = ga.rgba[i], db = gb.rgba[i];
        if (da < 0.0 || db < 0.0) {
            EXPECT_EQ(da < 0.0, db < 0.0);
            continue;
        }
        ++compared;
        if (std::abs(da - db) > 0.1 * pixel_rad * da * 10.0) ++off;  // 10: the steepest grazing the view has here
    }
    EXPECT_GT(compared, 64 * 48 / 3);
    EXPECT_EQ(off, 0);
    // And a second frame from the same camera is the same image.
    const Image g2 = (b.render(at_1au), b.read_geometry());
    EXPECT_EQ(g2.rgba, gb.rgba);
}

// The relief's shadows: the cone of the test above, no air, the Sun 1 degree high in the east at a
// point on the flat ground 50 km west of the peak (the cone's shadow reaches about 80 km). Flat ground that a ray march
// toward the Sun over the relief finds in the cone's shadow is dark; flat ground in the open beside it is lit.
TEST(TerrainRender, AtALowSunTheReliefCastsShadowsWhereARayMarchFindsThem) {
    context();
    const SceneConfig sc = lone_cone_scene("terrain_render_shadow");
    const BodyConfig& earth = sc.bodies[earth_id(sc)];
    const terrain::BodyRelief relief = terrain::open_body_relief(earth);
    const ChannelConfig ch = channel("down", FovDeg{20, 20, 20, 20}, 96, 96);
    const double radius = earth.radius_m;
    const Place lee = place(test::centric_deg(45.5), 10.25 - 0.65);
    const glm::dvec3 sun = glm::normalize(lee.east + std::tan(1.0 * kDeg) * lee.up);
    // 120 km over a point 60 km north of the lee point, looking straight down, north up: the
    // shadow (as wide as the cone, 110 km north to south, at its base) fills the view's southern part.
    const Place over = place(test::centric_deg(46.05), 10.25 - 0.65);
    const Snapshot s = snapshot(sc, glm::dvec3(0.0), over.up * (radius + 120e3), -over.up, over.north, sun);
    SceneRenderer r(cluster_of({ch}), ch, sc);
    const Image img = render_settled(r, s), g = r.read_geometry();
    double shadow_sum = 0.0, lit_sum = 0.0;
    int shadow_n = 0, lit_n = 0;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const float dist = g.rgba[4 * (static_cast<size_t>(y) * g.width + x) + 3];
            if (dist < 0.0f) continue;
            const glm::dvec3 hit = s.camera_position_m + static_cast<double>(dist) * pixel_ray(ch, s, x, y);
            const glm::dvec3 d = glm::normalize(hit);
            if (relief.relief->height_m(d, 0.0) > 1.0) continue;  // flat ground only: no slope's own shading
            // The relief's highest elevation toward the Sun, marched every 250 m over 120 km.
            const glm::dvec3 toward = glm::normalize(sun - d * glm::dot(sun, d));
            double horizon = -1.0;
            for (double a = 250.0; a < 120e3; a += 250.0) {
                const glm::dvec3 q = d * std::cos(a / radius) + toward * std::sin(a / radius);
                const glm::dvec3 p = q * (radius + relief.relief->height_m(q, 0.0)) - d * radius;
                horizon = std::max(horizon, glm::dot(p, d) / glm::length(p));
            }
            const double margin = glm::dot(sun, d) - horizon;
            if (std::abs(margin) < 0.011) continue;  // the soft edge (TERRAIN_SHADOW_EDGE and a quantum)
            (margin > 0.0 ? lit_sum : shadow_sum) += luminance(img, x, y);
            (margin > 0.0 ? lit_n : shadow_n) += 1;
        }
    ASSERT_GT(shadow_n, 40) << "the view must hold some of the cone's shadow";
    ASSERT_GT(lit_n, 40) << "and some open ground";
    const double shadow = shadow_sum / shadow_n, lit = lit_sum / lit_n;
    std::printf("flat ground: %d pixels in shadow at %.3g, %d lit at %.3g\n", shadow_n, shadow, lit_n, lit);
    EXPECT_GT(lit, 0.0);
    EXPECT_LT(shadow, 0.05 * lit);
    if (const char* out = std::getenv("CUPOLA_TERRAIN_IMAGES"))
        write_frame(std::string(out) + "/cone_shadow", img, FrameMetadata{}, {"exr"}, 1.0);
}

// Relief within ten radii of the camera, the sphere beyond; and the sphere in a frame whose sky
// is drawn first (its bodies beyond the air go to a colour target without a depth buffer).
TEST(TerrainRender, ABodyIsReliefWithinTenRadiiAndNeverWhenTheSkyIsDrawnFirst) {
    const SceneConfig sc = terrain_scene();
    const BodyConfig& earth = *sc.find("earth");
    BodyState state;
    state.id = earth.id;
    Snapshot snap;
    FrameContext f;
    f.snap = &snap;
    FrameBody b;
    b.state = &state;
    b.body = &earth;
    f.view.camera_position_m = glm::dvec3(0.0, 0.0, 9.9 * earth.radius_m);
    EXPECT_TRUE(draws_terrain(f, b));
    f.sky_first = true;
    EXPECT_FALSE(draws_terrain(f, b));
    f.sky_first = false;
    f.view.camera_position_m = glm::dvec3(0.0, 0.0, 10.1 * earth.radius_m);
    EXPECT_FALSE(draws_terrain(f, b));
    const SceneConfig smooth = test::earth_moon_scene();  // no terrain section: never
    b.body = smooth.find("earth");
    f.view.camera_position_m = glm::dvec3(0.0, 0.0, 1.1 * earth.radius_m);
    EXPECT_FALSE(draws_terrain(f, b));
}

namespace {

// The share of the Sun's disc the glare probe finds visible, once the tiles are built and the
// queries read back (a few frames of the same snapshot).
double sun_visible_fraction(SceneRenderer& r, const SceneConfig& sc, const Snapshot& s) {
    render_settled(r, s);
    for (int i = 0; i < 3; ++i) r.render(s);
    for (const GlareMeasurement& m : r.glare_measurements())
        if (m.body == sc.find("sun")->id && m.total_sr > 0.0f) return m.visible_total_sr() / m.total_sr;
    ADD_FAILURE() << "no measurement of the Sun";
    return -1.0;
}

}  // namespace

// 10 m above flat ground 50 km west of a 2000 m cone, looking east: with the Sun 1 degree up the
// cone (2.1 degrees high from there) hides all of its disc from the glare probe, as it hides it in
// the image; the smooth sphere would not; with the Sun 4 degrees up, above the cone, all of it is seen.
TEST(TerrainRender, AMountainHidesTheSunsGlareWhereTheSphereWouldNot) {
    context();
    const SceneConfig sc = lone_cone_scene("terrain_render_glare");
    const BodyConfig& earth = sc.bodies[earth_id(sc)];
    ASSERT_TRUE(sc.glare.enabled);
    const ChannelConfig ch = channel("east", FovDeg{20, 20, 20, 20}, 64, 64);
    const Place lee = place(test::centric_deg(45.5), 10.25 - 0.65);
    const glm::dvec3 camera = lee.up * (earth.radius_m + 10.0);
    const glm::dvec3 forward = glm::normalize(lee.east + std::tan(2.0 * kDeg) * lee.up);
    const auto sun_at = [&](double el_deg) {
        Snapshot s = snapshot(sc, glm::dvec3(0.0), camera, forward, lee.up,
                              glm::normalize(lee.east + std::tan(el_deg * kDeg) * lee.up));
        s.glare = GlareSources(sc, nullptr).select(s);
        return s;
    };
    SceneRenderer relief(cluster_of({ch}), ch, sc);
    const double hidden = sun_visible_fraction(relief, sc, sun_at(1.0));
    const double above = sun_visible_fraction(relief, sc, sun_at(4.0));
    SceneConfig smooth = sc;
    smooth.bodies[earth_id(sc)].terrain.present = false;
    SceneRenderer sphere(cluster_of({ch}), ch, smooth);
    const double over_the_sphere = sun_visible_fraction(sphere, smooth, sun_at(1.0));
    std::printf("Sun's disc seen: %.3f behind the cone, %.3f above it, %.3f over the smooth sphere\n", hidden, above,
                over_the_sphere);
    EXPECT_LT(hidden, 0.02);
    EXPECT_GT(above, 0.98);
    EXPECT_GT(over_the_sphere, 0.98);
}

// The real renderer on a real headless EGL context (llvmpipe on CI, a GPU on device nodes).
// Small images only: CI has 2 cores and a software rasteriser.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <tuple>

#include "gl/egl_context.hpp"
#include "gl/gl_api.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "projection/planar_screen.hpp"
#include "scene/star_catalog.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// One context for the whole executable, created with no window system in the environment.
EglContext& context() { return test::headless_gl(); }

struct OneStarScene {
    SceneConfig scene;
    double flux = 0.0;
    glm::dvec3 dir;
    explicit OneStarScene(double ra_deg, double dec_deg, double vmag, const std::string& tag) {
        const std::string dir_path = test::scratch_dir("EglRender_" + tag);
        scene.file = dir_path + "/scene.json";
        scene.stars.catalog = dir_path + "/one_star.csv";
        char line[128];
        std::snprintf(line, sizeof line, "%.6f,%.6f,%.2f,0.65,Test\n", ra_deg, dec_deg, vmag);
        test::write_text(scene.stars.catalog, std::string("ra_deg,dec_deg,vmag,bv,name\n") + line);
        scene.stars.magnitude_limit = 6.5;
        scene.stars.psf_sigma_arcmin = 2.0;
        scene.stars.zero_mag_flux = 2.0e-3;
        flux = scene.stars.zero_mag_flux * std::pow(10.0, -0.4 * vmag);
        dir = equatorial_direction(ra_deg * kDeg, dec_deg * kDeg);
    }
};

ChannelConfig channel(int w, int h, EulerDeg e, FovDeg f) {
    ChannelConfig c;
    c.id = 0;
    c.name = "test";
    c.width = w;
    c.height = h;
    c.orientation = e;
    c.fov = f;
    return c;
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// The brightest pixel's column, row and luminance (-1, -1, 0 for a black image).
std::tuple<int, int, double> brightest_pixel(const Image& img) {
    int bx = -1, by = -1;
    double best = 0.0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (luminance(img.pixel(x, y)) > best) best = luminance(img.pixel(x, y)), bx = x, by = y;
    return {bx, by, best};
}

}  // namespace

TEST(EglRender, HeadlessContextIsOpenGL45Core) {
    const auto& info = context().info();
    EXPECT_TRUE(info.platform == "device" || info.platform == "surfaceless") << info.platform;
    EXPECT_FALSE(info.renderer.empty());
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45) << info.version;
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_EQ(getenv("DISPLAY"), nullptr);
}

TEST(EglRender, MissingDeviceIsNamedInTheError) {
    context();
    try {
        EglContext other(1000);
        FAIL() << "device 1000 should not exist";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("EGL device 1000 requested but only"), std::string::npos) << e.what();
    }
}

TEST(EglRender, SharedFunctionsAgreeBetweenGpuAndCpu) {
    context();
    const int n = 32;
    GlFramebuffer fb(n, n);
    GlProgram prog("tests/fullscreen.vert", "tests/shared_eval.frag");
    GlEmptyVertexArray vao;
    fb.bind();
    prog.use();
    prog.set("u_size", glm::vec2(n, n));
    vao.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    const Image img = fb.read();
    namespace sh = cupola::shading;
    int checked_hits = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float a = (x + 0.5f) / n, b = (n - 1 - y + 0.5f) / n;  // image row 0 is the top
            const float sigma = 5.8e-4f;
            const float psf = sh::star_psf(a * 4.0f * sigma, sigma) * (2.0f * sh::CUPOLA_PI * sigma * sigma);
            const float ld = sh::limb_darkening(a, b);
            const sh::vec3 c = sh::bv_to_linear_srgb(-0.4f + 2.4f * a);
            const float col = c.x / std::max(c.z, 1e-6f) * 0.1f + c.y;
            const sh::vec4 hit =
                sh::sphere_hit(sh::normalize(sh::vec3(a - 0.5f, b - 0.5f, -1.0f)), sh::vec3(0, 0, -1), 0.3f);
            const float* p = img.pixel(x, y);
            ASSERT_NEAR(p[0], psf, 1e-4f * std::max(1.0f, psf)) << x << "," << y;
            ASSERT_NEAR(p[1], ld, 1e-5f) << x << "," << y;
            ASSERT_NEAR(p[2], col, 1e-3f * std::max(1.0f, col)) << x << "," << y;
            if (hit.w >= 0.0f) {
                // mu = sqrt(1 - rho^2) amplifies float error near the limb; compare mu^2 = 1 - rho^2.
                ASSERT_NEAR(p[3] * p[3], hit.w * hit.w, 1e-4f) << x << "," << y;
                ++checked_hits;
            } else {
                ASSERT_LT(p[3], 0.0f) << x << "," << y;
            }
        }
    EXPECT_GT(checked_hits, 50);
}

TEST(EglRender, StarLandsWherePixelMappingPredicts) {
    context();
    const OneStarScene s(30.0, 10.0, 0.0, "position");
    ClusterConfig cluster;  // tilt 0 and identity camera: dome frame = world frame
    // A channel looking at RA 30 (-Z towards it): yaw -(90-30)... simply rotate the camera instead.
    const ChannelConfig ch = channel(160, 120, {}, FovDeg{30, 25, 20, 28});
    SceneRenderer r(cluster, ch, s.scene);
    Snapshot snap;
    // Camera: -Z (forward) towards RA 33, Dec 8 so the star is off-centre; +Y roughly north.
    const glm::dvec3 fwd = equatorial_direction(33 * kDeg, 8 * kDeg);
    const glm::dvec3 right = glm::normalize(glm::cross(fwd, glm::dvec3(0, 0, 1)));
    const glm::dvec3 up = glm::cross(right, fwd);
    snap.camera_orientation = glm::quat_cast(glm::dmat3(right, up, -fwd));
    const Image img = r.render(snap);
    ASSERT_EQ(img.width, 160);
    ASSERT_EQ(img.height, 120);
    const auto [bx, by, best] = brightest_pixel(img);
    ASSERT_GT(best, 0.0) << "no star rendered";
    const glm::dvec3 dome_dir = glm::transpose(glm::mat3_cast(snap.camera_orientation)) * s.dir;
    const auto p = ch.frustum().dome_direction_to_pixel(dome_dir);
    ASSERT_TRUE(p);
    EXPECT_NEAR(bx + 0.5, p->x, 1.0);
    EXPECT_NEAR(by + 0.5, p->y, 1.0);
    // Nothing far from the star.
    EXPECT_EQ(luminance(img.pixel((bx + 80) % 160, (by + 60) % 120)), 0.0);
}

TEST(EglRender, StarEnergyIsTheSameInChannelsOfDifferentResolutionAndFov) {
    context();
    const OneStarScene s(120.0, -20.0, 1.0, "energy");
    ClusterConfig cluster;
    cluster.dome.tilt_deg = 15.0;
    Snapshot snap;  // identity camera
    // Dome-frame direction of the star, then two channels aimed near it with different setups.
    const glm::dvec3 cam_dir = s.dir;  // camera frame = world frame
    const glm::dvec3 dome_dir = glm::transpose(dome_tilt_rotation(cluster.dome.tilt_deg)) * cam_dir;
    const double yaw = std::atan2(dome_dir.x, -dome_dir.z) / kDeg;
    const double pitch = std::asin(dome_dir.y) / kDeg;
    const ChannelConfig a = channel(96, 96, {yaw + 5, pitch - 4, 0}, FovDeg{45, 45, 45, 45});     // ~56'/px
    const ChannelConfig b = channel(256, 200, {yaw - 2, pitch + 1, 20}, FovDeg{12, 18, 10, 16});  // ~7'/px
    double energy[2];
    int i = 0;
    for (const ChannelConfig* ch : {&a, &b}) {
        SceneRenderer r(cluster, *ch, s.scene);
        const Image img = r.render(snap);
        const ChannelFrustum f = ch->frustum();
        ASSERT_TRUE(f.contains(dome_dir));
        double e = 0.0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                e += luminance(img.pixel(x, y)) * f.pixel_solid_angle({x + 0.5, y + 0.5});
        energy[i++] = e;
    }
    RecordProperty("energy_ratio_a", std::to_string(energy[0] / s.flux));
    RecordProperty("energy_ratio_b", std::to_string(energy[1] / s.flux));
    EXPECT_NEAR(energy[0] / s.flux, 1.0, 0.03);
    EXPECT_NEAR(energy[1] / s.flux, 1.0, 0.03);
    EXPECT_NEAR(energy[0] / energy[1], 1.0, 0.03);
}

// The Sun of these tests: body 0, radiance 5.8e4 (a white Lambert surface at 1 AU reads 1).
BodyConfig unit_sun(double corona) {
    BodyConfig sun;
    sun.id = 0;
    sun.name = "Sun";
    sun.kind = BodyKind::Star;
    sun.radius_m = 6.957e8;
    sun.radiance = 5.8e4;
    sun.limb_darkening_u = 0.6;
    sun.corona = corona;
    return sun;
}

TEST(EglRender, SunDiscHasItsAngularSizeAndLimbDarkening) {
    context();
    OneStarScene s(0.0, -89.0, 6.0, "sun");
    s.scene.stars.magnitude_limit = -5.0;  // no stars
    const BodyConfig sun = unit_sun(0.0);  // the disc alone (the corona has its own test)
    s.scene.bodies = {sun};
    ClusterConfig cluster;
    const ChannelConfig ch = channel(128, 128, {}, FovDeg{1, 1, 1, 1});  // 2 degrees wide
    SceneRenderer r(cluster, ch, s.scene);
    Snapshot snap;
    const double d = 1.495978707e11;
    snap.camera_position_m = glm::dvec3(0, 0, d);  // -Z of the camera looks at the Sun (origin)
    snap.bodies = {BodyState{0, glm::dvec3(0.0), {1, 0, 0, 0}}};
    const Image img = r.render(snap);
    // Disc-centre radiance and darkening towards the limb.
    EXPECT_NEAR(img.pixel(64, 64)[0] / 5.8e4, 1.0, 0.01);
    const double alpha = std::asin(sun.radius_m / d);
    const double px_per_rad = 128 / (2 * std::tan(1 * kDeg));
    const int limb_px = static_cast<int>(std::floor(64 + std::tan(alpha) * px_per_rad));  // first pixel edge beyond
    EXPECT_GT(img.pixel(limb_px - 2, 64)[0], 0.0);
    EXPECT_LT(img.pixel(limb_px - 2, 64)[0], 0.7 * 5.8e4);
    EXPECT_EQ(img.pixel(limb_px + 1, 64)[0], 0.0f);
    // The disc's light: its area, pi * tan(alpha)^2 in pixels, times the mean of the darkened
    // disc, within 1 %. (A disc 17 pixels in radius is small enough for the limb's antialiasing:
    // a limb pixel carries the part of it the disc covers, so pixels are not counted.)
    double sum = 0.0;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) sum += img.pixel(x, y)[0];
    const double area_px = std::numbers::pi * std::pow(std::tan(alpha) * px_per_rad, 2);
    const double mean = 5.8e4 * shading::limb_darkening_disc_average(static_cast<float>(sun.limb_darkening_u));
    EXPECT_NEAR(sum / (area_px * mean), 1.0, 0.01);
}

// The corona around the disc: Baumbach's profile relative to the disc's mean radiance, out to
// six solar radii and nothing beyond (shaders/sun.frag).
TEST(EglRender, SunCoronaFollowsBaumbachsProfile) {
    context();
    OneStarScene s(0.0, -89.0, 6.0, "corona");
    s.scene.stars.magnitude_limit = -5.0;
    const BodyConfig sun = unit_sun(1.0);
    s.scene.bodies = {sun};
    ClusterConfig cluster;
    const ChannelConfig ch = channel(256, 256, {}, FovDeg{2, 2, 2, 2});
    SceneRenderer r(cluster, ch, s.scene);
    Snapshot snap;
    const double d = 1.495978707e11;
    snap.camera_position_m = glm::dvec3(0, 0, d);
    snap.bodies = {BodyState{0, glm::dvec3(0.0), {1, 0, 0, 0}}};
    const Image img = r.render(snap);
    const double alpha = std::asin(sun.radius_m / d);
    const double px_per_rad = 256 / (2 * std::tan(2 * kDeg));
    const double mean_disc = 5.8e4 * (1.0 - 0.6 / 3.0);
    auto baumbach = [](double rho) {
        return 1e-6 * (0.0532 * std::pow(rho, -2.5) + 1.425 * std::pow(rho, -7) + 2.565 * std::pow(rho, -17));
    };
    for (double rho : {1.5, 2.0, 3.0, 5.0}) {
        // Pixel centre nearest rho radii to the right of the centre (x = 128 + offset).
        const int x = static_cast<int>(std::floor(128 + std::tan(rho * alpha) * px_per_rad));
        const double rho_px = std::atan((x + 0.5 - 128) / px_per_rad) / alpha;
        EXPECT_NEAR(img.pixel(x, 128)[0] / (mean_disc * baumbach(rho_px)), 1.0, 0.02) << "rho " << rho_px;
    }
    const int beyond = static_cast<int>(std::ceil(128 + std::tan(6.2 * alpha) * px_per_rad));
    EXPECT_EQ(img.pixel(beyond, 128)[0], 0.0f);
    // The disc is still the disc.
    EXPECT_NEAR(img.pixel(128, 128)[0] / 5.8e4, 1.0, 0.01);
}

TEST(EglRender, WhiteLambertBodyAtOneAuIsAboutOne) {
    context();
    OneStarScene s(0.0, -89.0, 6.0, "lambert");
    s.scene.stars.magnitude_limit = -5.0;
    const BodyConfig sun = unit_sun(1.0);
    BodyConfig ball;
    ball.id = 1;
    ball.name = "Ball";
    ball.kind = BodyKind::Planet;
    ball.radius_m = 6.371e6;
    ball.albedo = 1.0;
    // A white texture file.
    const std::string dir = test::scratch_dir("EglRender_lambert_tex");
    ball.texture = dir + "/white.hdr";
    {
        std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
        for (int i = 0; i < 8; ++i) hdr += std::string("\x80\x80\x80\x81", 4);  // RGBE 1.0
        test::write_text(ball.texture, hdr);
    }
    s.scene.bodies = {sun, ball};
    ClusterConfig cluster;
    const ChannelConfig ch = channel(64, 64, {}, FovDeg{4, 4, 4, 4});
    SceneRenderer r(cluster, ch, s.scene);
    Snapshot snap;
    const double au = 1.495978707e11;
    const glm::dvec3 ball_pos(au, 0, 0);
    snap.bodies = {BodyState{0, glm::dvec3(0.0), {1, 0, 0, 0}}, BodyState{1, ball_pos, {1, 0, 0, 0}}};
    // Camera between the sun and the ball, 20 Earth radii from the ball, looking at it (full phase).
    snap.camera_position_m = ball_pos - glm::dvec3(20 * ball.radius_m, 0, 0);
    const glm::dvec3 fwd(1, 0, 0), up(0, 0, 1), right = glm::cross(fwd, up);
    snap.camera_orientation = glm::quat_cast(glm::dmat3(right, up, -fwd));
    const Image img = r.render(snap);
    const float* c = img.pixel(32, 32);
    EXPECT_NEAR(c[0], 1.0, 0.05);
    EXPECT_NEAR(c[1], 1.0, 0.05);
    EXPECT_NEAR(c[2], 1.0, 0.05);
    EXPECT_EQ(img.pixel(0, 0)[0], 0.0f);  // outside the disc (angular radius 2.87 deg, corner at 5.7)
}

// A channel given as a screen follows the snapshot's head: with the head at the default eye and
// 0.8 m to the right, 0.3 m down and 0.5 m back, the star lands where each frustum seen from that
// head predicts. A star is infinitely far: it keeps its direction, so it moves on the screen by
// the head's own sideways motion (no parallax of its own).
TEST(EglRender, AScreensChannelFollowsTheSnapshotsHead) {
    context();
    const OneStarScene s(30.0, 10.0, 0.0, "head");
    ClusterConfig cluster;
    cluster.room.eye_m = glm::dvec3(0.0, 1.5, 0.0);
    const PlanarScreen screen{{-1.5, 0.0, -1.5}, {-1.5, 3.0, -1.5}, {1.5, 3.0, -1.5}};
    const ScreenFrustum at_eye = screen_frustum(screen, cluster.room.eye_m);
    ChannelConfig ch = channel(160, 160, at_eye.orientation, at_eye.fov);
    ch.screen = screen;
    cluster.channels = {ch};
    SceneRenderer r(cluster, ch, s.scene);
    Snapshot snap;
    const glm::dvec3 fwd = equatorial_direction(33 * kDeg, 8 * kDeg);
    const glm::dvec3 right = glm::normalize(glm::cross(fwd, glm::dvec3(0, 0, 1)));
    snap.camera_orientation = glm::quat_cast(glm::dmat3(right, glm::cross(right, fwd), -fwd));
    const glm::dvec3 dome_dir = glm::transpose(glm::mat3_cast(snap.camera_orientation)) * s.dir;
    std::vector<glm::dvec2> seen;
    for (const glm::dvec3 head : {cluster.room.eye_m, glm::dvec3(0.8, 1.2, 0.5)}) {
        snap.head.position_m = head;
        snap.head.source = HeadSource::Tracked;
        const Image img = r.render(snap);
        const auto [bx, by, best] = brightest_pixel(img);
        ASSERT_GT(best, 0.0) << "no star rendered";
        const auto p = ch.frustum_seen_from(head).dome_direction_to_pixel(dome_dir);
        ASSERT_TRUE(p);
        EXPECT_NEAR(bx + 0.5, p->x, 1.0);
        EXPECT_NEAR(by + 0.5, p->y, 1.0);
        // The same from the room alone: where the ray from the head along the star's direction
        // meets the screen's plane (z = -1.5 m), 160 px over its 3 m from its upper-left corner.
        const glm::dvec3 hit = head + ((-1.5 - head.z) / dome_dir.z) * dome_dir;
        EXPECT_NEAR(p->x, (hit.x + 1.5) / 3.0 * 160.0, 1e-6);
        EXPECT_NEAR(p->y, (3.0 - hit.y) / 3.0 * 160.0, 1e-6);
        seen.push_back(*p);
    }
    EXPECT_GT(glm::length(seen[1] - seen[0]), 40.0) << "the star moved on the screen with the head";
}

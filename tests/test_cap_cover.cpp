// The fan over a sphere's cap (slave/passes/cap_cover.cpp) and its draw (sphere.vert, mode 2):
// on the CPU, every direction within the cone plus its margin lies in one of the fan's spherical
// triangles and the polygon is tight; on a real headless EGL context (llvmpipe on CI), the
// pixels the fan covers include every pixel whose ray meets the sphere, in the hard cases: the
// Earth from 2 m above the ground (a cap of 89.95 degrees, its rim behind the camera), a sphere
// behind the camera, one much smaller than a pixel, one half off the channel, and a camera just
// outside the sphere (a cap wider than the view).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>

#include "gl/egl_context.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "passes/cap_cover.hpp"
#include "passes/sphere_billboard.hpp"
#include "image/frame_image.hpp"
#include "shading/shared_shading.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Is v inside the fan's spherical triangle (axis, rim i, rim i+1) for some i?
bool in_fan(const CapCover& c, const glm::dvec3& v) {
    const glm::dvec3 a = c.directions[0];
    for (int i = 1; i <= kCapCoverRim; ++i) {
        const glm::dvec3 p = c.directions[i], q = c.directions[i + 1];
        const double s1 = glm::dot(glm::cross(a, p), v), s2 = glm::dot(glm::cross(p, q), v),
                     s3 = glm::dot(glm::cross(q, a), v);
        if (s1 >= -1e-12 && s2 >= -1e-12 && s3 >= -1e-12) return true;
    }
    return false;
}

// A direction at angle theta from the unit axis, at azimuth phi about it.
glm::dvec3 around(const glm::dvec3& axis, double theta, double phi) {
    const glm::dvec3 h = std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(axis, h)), e2 = glm::cross(axis, e1);
    return std::cos(theta) * axis + std::sin(theta) * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

EglContext& context() { return test::headless_gl(); }

}  // namespace

TEST(CapCover, EveryDirectionOfTheConeAndItsMarginIsInTheFan) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (double cone_deg : {1e-4, 0.25, 10.0, 45.0, 80.0, 89.95, 95.0, 120.0, 170.0}) {
        const glm::dvec3 axis = glm::normalize(glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
        const double margin = 0.01 * kDeg;
        const CapCover c = cap_cover(axis, cone_deg * kDeg, margin);
        ASSERT_TRUE(c.valid) << cone_deg;
        for (int k = 0; k < 4000; ++k) {
            // Most samples on the boundary, where a fan that is too small fails first.
            const double theta = (k % 2 ? 1.0 : u(rng)) * (cone_deg * kDeg + margin);
            const glm::dvec3 v = around(axis, theta, 2.0 * std::numbers::pi * u(rng));
            ASSERT_TRUE(in_fan(c, v)) << "cone " << cone_deg << " theta " << theta / kDeg;
        }
        // Tight: the polygon's nearest boundary is the cone plus its margin (to rounding), and no
        // rim direction lies farther out than the edge bulge needs (cos of half a rim step).
        EXPECT_NEAR(cap_cover_inner_rad(c.rim_rad), cone_deg * kDeg + margin, 1e-9) << cone_deg;
        // Its farthest boundary: the rim directions, or past 90 degrees the edge midpoints.
        const double half_step = std::numbers::pi / kCapCoverRim;
        const double outer =
            std::max(c.rim_rad, std::atan2(std::sin(c.rim_rad) * std::cos(half_step), std::cos(c.rim_rad)));
        for (double phi = 0.0; phi < 6.3; phi += 0.1)
            EXPECT_FALSE(in_fan(c, around(axis, outer + 1e-6, phi))) << cone_deg << " " << phi;
    }
}

TEST(CapCover, ANearlyFullSphereOfDirectionsHasNoFan) {
    EXPECT_FALSE(cap_cover(glm::dvec3(0, 0, -1), 176.0 * kDeg, 0.0).valid);
    EXPECT_TRUE(cap_cover(glm::dvec3(0, 0, -1), 174.0 * kDeg, 0.0).valid);
}

namespace {
// Renders the cover of a sphere (centre in the channel frame, metres) into a 256 x 192 channel and
// checks it against the pixels whose rays meet the sphere. Returns the covered pixel count. Writes
// build/test-tmp/CapCover_<name>-<hash>/<name>.png to look at: blue where the ray meets the sphere, red where
// the fan covers a pixel that does not show it, black elsewhere.
int check_cover(const std::string& name, const glm::dvec3& center_m, double radius_m, int& hits) {
    context();
    const ChannelFrustum f(EulerDeg{0, 0, 0}, FovDeg{40, 50, 35, 45}, 256, 192);
    ChannelView view;
    view.frustum = &f;
    const SphereView s = make_sphere_view(view, center_m, radius_m);
    GlFramebuffer fb(f.width(), f.height());
    fb.bind();
    fb.clear(0, glm::vec4(0.0f));
    GlProgram program("sphere.vert", "tests/cover_mask.frag");
    program.use();
    GlEmptyVertexArray vao;
    vao.bind();
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    draw_cover(program, view, s);
    const Image img = fb.read();
    Image look = img;
    int covered = 0;
    hits = 0;
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x) {
            const glm::vec3 v = shading::channel_ray(glm::vec2(x + 0.5f, y + 0.5f), view.size(), view.tangents());
            const bool hit = shading::sphere_hit(v, glm::vec3(s.center_dir), static_cast<float>(s.sin_alpha)).w >= 0.0f;
            const bool on = img.pixel(x, f.height() - 1 - y)[0] > 0.5f;  // row 0 of the image is the top
            covered += on ? 1 : 0;
            hits += hit ? 1 : 0;
            EXPECT_TRUE(on || !hit) << "pixel " << x << "," << y << " shows the sphere but is not covered";
            float* px = look.pixel(x, f.height() - 1 - y);
            px[0] = on && !hit ? 1.0f : 0.0f;
            px[1] = 0.0f;
            px[2] = hit ? 1.0f : 0.0f;
            px[3] = 1.0f;
        }
    FrameMetadata meta;
    meta.channel_name = name;
    const std::string dir = test::scratch_dir("CapCover_" + name);
    const auto paths = write_frame(dir, look, meta, {"png"}, 1.0);
    std::filesystem::rename(paths.at(0), dir + "/" + name + ".png");
    return covered;
}
}  // namespace

TEST(CapCoverRender, TheFanCoversEveryPixelOfTheSphereInTheHardCases) {
    int hits = 0;
    // The Earth from 2 m above the ground, the channel looking 20 degrees above the horizon: the
    // ground fills the lower part; the fan's rim lies behind the camera.
    const double R = 6.371e6;
    const glm::dvec3 nadir(0.0, -std::cos(20.0 * kDeg), std::sin(20.0 * kDeg));  // the view 20 degrees up
    int covered = check_cover("earth-from-2m", (R + 2.0) * nadir, R, hits);
    EXPECT_GT(hits, 1000);
    EXPECT_LT(covered, hits + 8 * 256);  // a few rows of margin, not the whole channel
    // Behind the camera: nothing hit, nothing covered.
    covered = check_cover("behind", glm::dvec3(0, 0, 1.0e7), 1.0e6, hits);
    EXPECT_EQ(hits, 0);
    EXPECT_EQ(covered, 0);
    // Much smaller than a pixel, off-centre: covered by a few pixels.
    covered = check_cover("sub-pixel", glm::dvec3(0.1e9, 0.05e9, -1.0e9), 10.0, hits);
    EXPECT_GE(covered, 1);
    EXPECT_LE(covered, 36);
    // Half off the channel's right edge.
    covered = check_cover("half-off", glm::dvec3(1.2e9, 0.0, -1.0e9), 2.0e8, hits);
    EXPECT_GT(hits, 100);
    EXPECT_LT(covered, 256 * 192);
    // Just outside a sphere ahead: a cap wider than the view covers all of it.
    covered = check_cover("just-outside", glm::dvec3(0.0, 0.0, -1.0001e6), 1.0e6, hits);
    EXPECT_EQ(hits, 256 * 192);
    EXPECT_EQ(covered, 256 * 192);
}

// Stars behind the largest body on screen are not drawn (shaders/stars.vert, StarPass): on a real
// headless EGL context (llvmpipe on CI), a star deep inside the body's disc leaves its pixels
// black, one just inside the disc's edge (within its PSF's reach of it) and one outside are drawn,
// and without an occluder all three are. The body pass (or the atmosphere, relighting the ground)
// paints the disc over opaque, so a frame
// does not change; the scene tests (test_egl_render, test_atmosphere_stars) check the frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "gl/egl_context.hpp"
#include "gl/gl_framebuffer.hpp"
#include "passes/star_pass.hpp"
#include "projection/channel_frustum.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr int kSize = 128;

EglContext& context() { return test::headless_gl(); }

// The direction `below_deg` under the view axis (-z), as a catalogue star (the channel frame is
// the world frame here).
Star star_below(double below_deg) {
    const glm::dvec3 d(0.0, -std::sin(below_deg * kDeg), -std::cos(below_deg * kDeg));
    Star s;
    s.dec_rad = std::asin(d.z);
    s.ra_rad = std::atan2(d.y, d.x);
    s.v_mag = 0.0f;
    return s;
}

// The brightest value within 4 px of where a direction `below_deg` under the axis lands.
float peak_near(const Image& img, const ChannelFrustum& f, double below_deg) {
    const double ty = -std::tan(below_deg * kDeg);
    const int x = kSize / 2, y = static_cast<int>((ty + f.tan_down()) / (f.tan_down() + f.tan_up()) * kSize);
    float m = 0.0f;
    for (int j = std::max(0, y - 4); j <= std::min(kSize - 1, y + 4); ++j)
        for (int i = x - 4; i <= x + 4; ++i) m = std::max(m, img.pixel(i, kSize - 1 - j)[1]);  // row 0: top
    return m;
}

Image render(StarPass& pass, StarOccluder occluder, const ChannelFrustum& f) {
    ChannelView view;
    view.frustum = &f;
    GlFramebuffer fb(kSize, kSize);
    fb.bind();
    fb.clear(0, glm::vec4(0.0f));
    pass.draw(view, 10.0, 1.0, occluder);
    return fb.read();
}

}  // namespace

TEST(StarOccluder, AStarWhollyBehindTheLargestBodyIsNotDrawnOneNearItsEdgeIs) {
    context();
    const ChannelFrustum f(EulerDeg{0, 0, 0}, FovDeg{30, 30, 30, 30}, kSize, kSize);
    StarFieldConfig config;
    config.psf_sigma_arcmin = 10.0;
    // Deep inside the disc, 0.1 degrees inside its edge (within the PSF's reach), and above it.
    StarPass pass(config, {star_below(15.0), star_below(5.1), star_below(-5.0)});
    // A body whose disc (15 degrees in radius) is centred 20 degrees under the axis: its edge 5 under.
    StarOccluder body;
    body.center_dir = glm::vec3(0.0f, -std::sin(20.0 * kDeg), -std::cos(20.0 * kDeg));
    body.radius_rad = static_cast<float>(15.0 * kDeg);
    const Image hidden = render(pass, body, f), open = render(pass, {}, f);
    EXPECT_EQ(peak_near(hidden, f, 15.0), 0.0f) << "the star behind the body was drawn";
    EXPECT_GT(peak_near(open, f, 15.0), 0.0f) << "without an occluder every star is drawn";
    for (double below : {5.1, -5.0}) {
        EXPECT_GT(peak_near(hidden, f, below), 0.0f) << below;
        EXPECT_EQ(peak_near(hidden, f, below), peak_near(open, f, below)) << below;
    }
}

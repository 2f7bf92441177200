// ChannelFrustum and the dome-frame orientation conventions against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "projection/channel_frustum.hpp"
#include "projection/dome_frame.hpp"

using namespace cupola;

namespace {

void expect_vec_near(const glm::dvec3& a, const glm::dvec3& b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// Analytic solid angle of the rectangle [x1,x2]x[y1,y2] on the plane z = -1 seen from the origin.
double rect_solid_angle(double x1, double x2, double y1, double y2) {
    auto F = [](double x, double y) { return std::atan(x * y / std::sqrt(1.0 + x * x + y * y)); };
    return F(x2, y2) - F(x1, y2) - F(x2, y1) + F(x1, y1);
}

}  // namespace

// glFrustum with l = -n tan(left), r = n tan(right), b = -n tan(down), t = n tan(up):
//   [ 2n/(r-l)   0          (r+l)/(r-l)   0           ]
//   [ 0          2n/(t-b)   (t+b)/(t-b)   0           ]
//   [ 0          0          -(f+n)/(f-n)  -2fn/(f-n)  ]
//   [ 0          0          -1            0           ]
TEST(Frustum, AsymmetricProjectionMatchesHandComputedValues) {
    // left 30, right 60, up 45, down 20, near 1, far 100.
    //   r - l = tan60 + tan30 = sqrt3 + 1/sqrt3 = 4/sqrt3   -> 2/(r-l) = sqrt3/2 = 0.8660254037844386
    //   r + l = tan60 - tan30 = 2/sqrt3                     -> (r+l)/(r-l) = 0.5
    //   t - b = 1 + tan20 = 1.36397023426620234            -> 2/(t-b) = 1.4663076581549987
    //   t + b = 1 - tan20                                   -> (t+b)/(t-b) = tan25 = 0.4663076581549986
    //   -(f+n)/(f-n) = -101/99 = -1.0202020202020202, -2fn/(f-n) = -200/99 = -2.0202020202020203
    const ChannelFrustum f(EulerDeg{}, FovDeg{30, 60, 45, 20}, 640, 480);
    const glm::dmat4 m = f.projection(1.0, 100.0);
    const double tol = 1e-12;
    // glm is column-major: m[column][row].
    EXPECT_NEAR(m[0][0], 0.8660254037844386, tol);
    EXPECT_NEAR(m[1][0], 0.0, tol);
    EXPECT_NEAR(m[2][0], 0.5, tol);
    EXPECT_NEAR(m[3][0], 0.0, tol);
    EXPECT_NEAR(m[0][1], 0.0, tol);
    EXPECT_NEAR(m[1][1], 1.4663076581549987, tol);
    EXPECT_NEAR(m[2][1], 0.4663076581549986, tol);
    EXPECT_NEAR(m[3][1], 0.0, tol);
    EXPECT_NEAR(m[0][2], 0.0, tol);
    EXPECT_NEAR(m[1][2], 0.0, tol);
    EXPECT_NEAR(m[2][2], -1.0202020202020202, tol);
    EXPECT_NEAR(m[3][2], -2.0202020202020203, tol);
    EXPECT_NEAR(m[0][3], 0.0, tol);
    EXPECT_NEAR(m[1][3], 0.0, tol);
    EXPECT_NEAR(m[2][3], -1.0, tol);
    EXPECT_NEAR(m[3][3], 0.0, tol);
}

TEST(Frustum, SymmetricProjectionMatchesHandComputedValues) {
    // 45/45/45/45, near 0.5, far 10: 2n/(r-l) = 1/tan45 = 1, no off-centre terms,
    // -(f+n)/(f-n) = -10.5/9.5, -2fn/(f-n) = -10/9.5.
    const ChannelFrustum f(EulerDeg{}, FovDeg{45, 45, 45, 45}, 256, 256);
    const glm::dmat4 m = f.projection(0.5, 10.0);
    const double tol = 1e-12;
    EXPECT_NEAR(m[0][0], 1.0, tol);
    EXPECT_NEAR(m[1][1], 1.0, tol);
    EXPECT_NEAR(m[2][0], 0.0, tol);
    EXPECT_NEAR(m[2][1], 0.0, tol);
    EXPECT_NEAR(m[2][2], -1.1052631578947369, tol);
    EXPECT_NEAR(m[3][2], -1.0526315789473684, tol);
    EXPECT_NEAR(m[2][3], -1.0, tol);
    EXPECT_NEAR(m[3][3], 0.0, tol);
    EXPECT_NEAR(m[0][1], 0.0, tol);
    EXPECT_NEAR(m[1][0], 0.0, tol);
}

// The GL projection (what the slave renders) and dome_direction_to_pixel (what the stitcher
// samples) must agree: NDC x -1..1 is pixel x 0..width, NDC y +1..-1 is pixel y 0..height.
TEST(Frustum, ProjectionAgreesWithPixelMapping) {
    const ChannelFrustum f(EulerDeg{25, 35, -10}, FovDeg{30, 60, 45, 20}, 640, 480);
    const glm::dmat4 m = f.projection(0.1, 1000.0);
    for (double px : {0.0, 17.5, 320.0, 639.0, 640.0})
        for (double py : {0.0, 100.25, 240.0, 480.0}) {
            const glm::dvec3 dome = f.pixel_to_dome_direction({px, py});
            const glm::dvec3 cam = glm::transpose(f.rotation()) * dome * 5.0;  // channel frame point
            const glm::dvec4 clip = m * glm::dvec4(cam, 1.0);
            const double ndc_x = clip.x / clip.w, ndc_y = clip.y / clip.w;
            EXPECT_NEAR((ndc_x + 1.0) * 0.5 * 640, px, 1e-9);
            EXPECT_NEAR((1.0 - ndc_y) * 0.5 * 480, py, 1e-9);
            const auto back = f.dome_direction_to_pixel(dome);
            ASSERT_TRUE(back);
            EXPECT_NEAR(back->x, px, 1e-9);
            EXPECT_NEAR(back->y, py, 1e-9);
        }
}

// dome_frame.hpp: yaw positive turns the view right (about -Y), pitch positive raises it (about
// +X), roll positive turns the image clockwise as seen by the viewer (about -Z); R = Ryaw Rpitch Rroll.
TEST(Frustum, ChannelRotationConventions) {
    const glm::dvec3 forward(0, 0, -1), up(0, 1, 0), right(1, 0, 0);
    const double tol = 1e-12;
    // Identity.
    expect_vec_near(channel_rotation({0, 0, 0}) * forward, forward, tol);
    // Yaw 90: looking right (+X); up unchanged; channel right now points to the back (+Z).
    expect_vec_near(channel_rotation({90, 0, 0}) * forward, {1, 0, 0}, tol);
    expect_vec_near(channel_rotation({90, 0, 0}) * up, up, tol);
    expect_vec_near(channel_rotation({90, 0, 0}) * right, {0, 0, 1}, tol);
    // Yaw -90: looking left.
    expect_vec_near(channel_rotation({-90, 0, 0}) * forward, {-1, 0, 0}, tol);
    // Pitch 90: looking at the apex (+Y); channel up points to the back (+Z).
    expect_vec_near(channel_rotation({0, 90, 0}) * forward, {0, 1, 0}, tol);
    expect_vec_near(channel_rotation({0, 90, 0}) * up, {0, 0, 1}, tol);
    expect_vec_near(channel_rotation({0, 90, 0}) * right, right, tol);
    // Roll 90: forward unchanged; the channel's up turns clockwise to the viewer's right (+X).
    expect_vec_near(channel_rotation({0, 0, 90}) * forward, forward, tol);
    expect_vec_near(channel_rotation({0, 0, 90}) * up, {1, 0, 0}, tol);
    expect_vec_near(channel_rotation({0, 0, 90}) * right, {0, -1, 0}, tol);
    // Order: yaw 90 then pitch 45 looks right and 45 deg up; roll does not move forward.
    const double h = std::sqrt(0.5);
    expect_vec_near(channel_rotation({90, 45, 0}) * forward, {h, h, 0}, tol);
    expect_vec_near(channel_rotation({90, 45, 30}) * forward, {h, h, 0}, tol);
    // Pitch is about the yawed right axis, not the dome's X: yaw 90, pitch 90 still looks at the apex
    // and its up vector points to the dome's left (-X) ... (forward of the yawed view is +X).
    expect_vec_near(channel_rotation({90, 90, 0}) * forward, {0, 1, 0}, tol);
    expect_vec_near(channel_rotation({90, 90, 0}) * up, {-1, 0, 0}, tol);
    // Proper rotation.
    const glm::dmat3 r = channel_rotation({17, -33, 71});
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-12);
    const glm::dmat3 i = glm::transpose(r) * r;
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(i[c][k], c == k ? 1.0 : 0.0, 1e-12);
}

TEST(Frustum, DomeTiltMovesTheApexTowardsTheFront) {
    // Dome -> camera: a dome tilted 30 deg has its apex 30 deg from +Y towards -Z.
    const glm::dvec3 apex = dome_tilt_rotation(30.0) * glm::dvec3(0, 1, 0);
    expect_vec_near(apex, {0, std::cos(glm::radians(30.0)), -std::sin(glm::radians(30.0))}, 1e-12);
    expect_vec_near(dome_tilt_rotation(30.0) * glm::dvec3(1, 0, 0), {1, 0, 0}, 1e-12);
}

TEST(Frustum, PixelMappingOfAxisAndCorners) {
    // Unrotated, asymmetric: the optical axis (0,0,-1) lands where tan(left)/(tan(left)+tan(right))
    // of the width is, and tan(up)/(tan(up)+tan(down)) of the height from the top.
    const ChannelFrustum f(EulerDeg{}, FovDeg{30, 60, 45, 20}, 640, 480);
    const auto axis = f.dome_direction_to_pixel({0, 0, -1});
    ASSERT_TRUE(axis);
    const double t30 = std::tan(glm::radians(30.0)), t60 = std::tan(glm::radians(60.0));
    const double t20 = std::tan(glm::radians(20.0));
    EXPECT_NEAR(axis->x, 640 * t30 / (t30 + t60), 1e-9);  // = 160: tan30/(tan30+tan60) = 1/4
    EXPECT_NEAR(axis->x, 160.0, 1e-9);
    EXPECT_NEAR(axis->y, 480 * 1.0 / (1.0 + t20), 1e-9);
    // Top-left corner: 30 deg left, 45 deg up.
    const glm::dvec3 tl = f.pixel_to_dome_direction({0, 0});
    expect_vec_near(tl, glm::normalize(glm::dvec3(-t30, 1.0, -1.0)), 1e-12);
    // Bottom-right corner: 60 deg right, 20 deg down.
    const glm::dvec3 br = f.pixel_to_dome_direction({640, 480});
    expect_vec_near(br, glm::normalize(glm::dvec3(t60, -t20, -1.0)), 1e-12);
    // Behind the projector.
    EXPECT_FALSE(f.dome_direction_to_pixel({0, 0, 1}));
    EXPECT_FALSE(f.dome_direction_to_pixel({1, 0, 0}));
}

TEST(Frustum, PixelDirectionRoundTrip) {
    for (const EulerDeg& e : {EulerDeg{0, 0, 0}, EulerDeg{60, 20, 0}, EulerDeg{-135, 70, 15}, EulerDeg{10, -5, -90}}) {
        const ChannelFrustum f(e, FovDeg{30, 60, 45, 20}, 320, 200);
        for (int j = 0; j <= 20; ++j)
            for (int i = 0; i <= 20; ++i) {
                const glm::dvec2 p(320.0 * i / 20, 200.0 * j / 20);
                const glm::dvec3 d = f.pixel_to_dome_direction(p);
                EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
                const auto back = f.dome_direction_to_pixel(d);
                ASSERT_TRUE(back);
                EXPECT_NEAR(back->x, p.x, 1e-9);
                EXPECT_NEAR(back->y, p.y, 1e-9);
                // And direction -> pixel -> direction.
                const glm::dvec3 d2 = f.pixel_to_dome_direction(*back);
                expect_vec_near(d2, d, 1e-12);
            }
    }
}

TEST(Frustum, ContainsAtEdges) {
    const ChannelFrustum f(EulerDeg{40, 10, 5}, FovDeg{30, 60, 45, 20}, 320, 200);
    const double eps = 1e-6;  // pixels
    // Just inside each edge, and the centre.
    for (glm::dvec2 p :
         {glm::dvec2(eps, 100), glm::dvec2(320 - eps, 100), glm::dvec2(160, eps), glm::dvec2(160, 200 - eps),
          glm::dvec2(eps, eps), glm::dvec2(320 - eps, 200 - eps), glm::dvec2(160, 100)})
        EXPECT_TRUE(f.contains(f.pixel_to_dome_direction(p))) << p.x << "," << p.y;
    // Just outside each edge (directions extrapolated beyond the image).
    for (glm::dvec2 p : {glm::dvec2(-1e-3, 100), glm::dvec2(320 + 1e-3, 100), glm::dvec2(160, -1e-3),
                         glm::dvec2(160, 200 + 1e-3), glm::dvec2(-5, -5)})
        EXPECT_FALSE(f.contains(f.pixel_to_dome_direction(p))) << p.x << "," << p.y;
    // Behind the projector.
    EXPECT_FALSE(f.contains(-f.pixel_to_dome_direction({160, 100})));
    // Edge distance: positive inside, zero on the edge, negative outside.
    EXPECT_NEAR(f.edge_distance_px({160, 100}), 100.0, 1e-12);
    EXPECT_NEAR(f.edge_distance_px({3, 100}), 3.0, 1e-12);
    EXPECT_NEAR(f.edge_distance_px({160, 198}), 2.0, 1e-12);
    EXPECT_NEAR(f.edge_distance_px({0, 50}), 0.0, 1e-12);
    EXPECT_NEAR(f.edge_distance_px({-2, 50}), -2.0, 1e-12);
}

TEST(Frustum, PixelSolidAnglesSumToThePyramid) {
    struct Case {
        FovDeg fov;
        int w, h;
    };
    for (const Case& c :
         {Case{{45, 45, 45, 45}, 256, 256}, Case{{30, 60, 45, 20}, 240, 160}, Case{{10, 50, 5, 35}, 200, 256}}) {
        const ChannelFrustum f(EulerDeg{33, 12, -7}, c.fov, c.w, c.h);
        double sum = 0.0;
        for (int y = 0; y < c.h; ++y)
            for (int x = 0; x < c.w; ++x) sum += f.pixel_solid_angle({x + 0.5, y + 0.5});
        const double expected = rect_solid_angle(-f.tan_left(), f.tan_right(), -f.tan_down(), f.tan_up());
        EXPECT_NEAR(sum, expected, 1e-3 * expected) << c.fov.left_deg << "/" << c.fov.right_deg;
    }
    // The analytic formula itself: a 90x90 deg square pyramid is 2 pi / 3 sr (a cube face), and the
    // asymmetric 30/60/45/20 pyramid is 1.492989609207283 sr (computed by hand from the same formula).
    EXPECT_NEAR(rect_solid_angle(-1, 1, -1, 1), 2.0 * M_PI / 3.0, 1e-12);
    EXPECT_NEAR(rect_solid_angle(-std::tan(glm::radians(30.0)), std::tan(glm::radians(60.0)),
                                 -std::tan(glm::radians(20.0)), 1.0),
                1.492989609207283, 1e-12);
    // The pixel at the optical axis of a 45/45 square 256x256 channel: (2/256)^2 sr.
    const ChannelFrustum sq(EulerDeg{}, FovDeg{45, 45, 45, 45}, 256, 256);
    EXPECT_NEAR(sq.pixel_solid_angle({128, 128}), (2.0 / 256) * (2.0 / 256), 1e-15);
    // At a corner (x = y = 1 on the plane) the projection factor is 1/3^1.5.
    EXPECT_NEAR(sq.pixel_solid_angle({0, 0}), (2.0 / 256) * (2.0 / 256) / std::pow(3.0, 1.5), 1e-15);
}

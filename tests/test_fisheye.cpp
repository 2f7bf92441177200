// Angular fisheye (domemaster) mapping: Paul Bourke's convention in the dome frame.
#include <gtest/gtest.h>

#include <cmath>

#include "projection/fisheye.hpp"

using namespace cupola;

namespace {

void expect_vec_near(const glm::dvec3& a, const glm::dvec3& b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

TEST(Fisheye, UvDirectionRoundTripOverAGrid) {
    for (double fov : {180.0, 210.0, 150.0}) {
        const FisheyeMapping fish(fov);
        int inside = 0;
        for (int j = 0; j <= 60; ++j)
            for (int i = 0; i <= 60; ++i) {
                const glm::dvec2 uv(-1.0 + 2.0 * i / 60, -1.0 + 2.0 * j / 60);
                const auto d = fish.uv_to_direction(uv);
                if (glm::length(uv) > 1.0) {
                    EXPECT_FALSE(d) << uv.x << "," << uv.y;
                    continue;
                }
                ASSERT_TRUE(d);
                ++inside;
                EXPECT_NEAR(glm::length(*d), 1.0, 1e-12);
                // The angle from the apex is proportional to the radius.
                EXPECT_NEAR(angle_between(*d, {0, 1, 0}), glm::length(uv) * fish.half_fov_rad(), 1e-9);
                const auto back = fish.direction_to_uv(*d);
                ASSERT_TRUE(back) << uv.x << "," << uv.y;
                EXPECT_NEAR(back->x, uv.x, 1e-9);
                EXPECT_NEAR(back->y, uv.y, 1e-9);
            }
        EXPECT_GT(inside, 2500);
    }
}

TEST(Fisheye, PixelUvRoundTrip) {
    const int size = 512;
    EXPECT_EQ(FisheyeMapping::pixel_to_uv({0, 0}, size), glm::dvec2(-1, 1));      // top-left corner
    EXPECT_EQ(FisheyeMapping::pixel_to_uv({512, 512}, size), glm::dvec2(1, -1));  // bottom-right
    EXPECT_EQ(FisheyeMapping::pixel_to_uv({256, 256}, size), glm::dvec2(0, 0));   // centre
    EXPECT_EQ(FisheyeMapping::uv_to_pixel({0, -1}, size), glm::dvec2(256, 512));  // bottom-centre
    for (double y = 0.25; y < size; y += 37.3)
        for (double x = 0.5; x < size; x += 41.7) {
            const glm::dvec2 uv = FisheyeMapping::pixel_to_uv({x, y}, size);
            const glm::dvec2 p = FisheyeMapping::uv_to_pixel(uv, size);
            EXPECT_NEAR(p.x, x, 1e-9);
            EXPECT_NEAR(p.y, y, 1e-9);
        }
}

TEST(Fisheye, LandmarksOfTheDomemaster) {
    const FisheyeMapping fish(180.0);
    // Centre = apex.
    expect_vec_near(*fish.uv_to_direction({0, 0}), {0, 1, 0}, 1e-15);
    EXPECT_NEAR(fish.direction_to_uv({0, 1, 0})->x, 0.0, 1e-15);
    EXPECT_NEAR(fish.direction_to_uv({0, 1, 0})->y, 0.0, 1e-15);
    // Bottom-centre of the rim = front of the dome (-Z).
    expect_vec_near(*fish.uv_to_direction({0, -1}), {0, 0, -1}, 1e-12);
    // Right rim = the audience's right (+X); left rim = -X; top rim = back (+Z).
    expect_vec_near(*fish.uv_to_direction({1, 0}), {1, 0, 0}, 1e-12);
    expect_vec_near(*fish.uv_to_direction({-1, 0}), {-1, 0, 0}, 1e-12);
    expect_vec_near(*fish.uv_to_direction({0, 1}), {0, 0, 1}, 1e-12);
    // In pixels of a 1024 image: front at the bottom-centre, right at the right-centre.
    const glm::dvec2 front = FisheyeMapping::uv_to_pixel(*fish.direction_to_uv({0, 0, -1}), 1024);
    EXPECT_NEAR(front.x, 512.0, 1e-9);
    EXPECT_NEAR(front.y, 1024.0, 1e-9);
    const glm::dvec2 right = FisheyeMapping::uv_to_pixel(*fish.direction_to_uv({1, 0, 0}), 1024);
    EXPECT_NEAR(right.x, 1024.0, 1e-9);
    EXPECT_NEAR(right.y, 512.0, 1e-9);
}

TEST(Fisheye, RadiusIsProportionalToAngle) {
    const FisheyeMapping fish(180.0);
    const double s = std::sqrt(0.5);
    // 45 deg from the apex towards the front: r = 45/90 = 0.5, straight down the image.
    const auto uv = fish.direction_to_uv({0, s, -s});
    ASSERT_TRUE(uv);
    EXPECT_NEAR(uv->x, 0.0, 1e-12);
    EXPECT_NEAR(uv->y, -0.5, 1e-12);
    // 45 deg towards the right-front diagonal: r = 0.5 along the lower-right diagonal.
    const auto uv2 = fish.direction_to_uv(glm::normalize(glm::dvec3(0.5, s, -0.5)));
    ASSERT_TRUE(uv2);
    EXPECT_NEAR(glm::length(*uv2), 0.5, 1e-12);
    EXPECT_NEAR(uv2->x, 0.5 * s, 1e-12);
    EXPECT_NEAR(uv2->y, -0.5 * s, 1e-12);
    // Equal angle steps give equal radius steps (f-theta, not f-tan or equisolid).
    for (int k = 0; k <= 9; ++k) {
        const double a = glm::radians(10.0 * k);
        const auto p = fish.direction_to_uv({std::sin(a), std::cos(a), 0});
        ASSERT_TRUE(p);
        EXPECT_NEAR(p->x, k / 9.0, 1e-12);
        EXPECT_NEAR(p->y, 0.0, 1e-12);
    }
    // Unnormalised input is accepted.
    const auto uv3 = fish.direction_to_uv({0, 5 * s, -5 * s});
    ASSERT_TRUE(uv3);
    EXPECT_NEAR(uv3->y, -0.5, 1e-12);
}

TEST(Fisheye, WiderThanAHemisphere) {
    const FisheyeMapping fish(210.0);
    EXPECT_NEAR(fish.half_fov_rad(), glm::radians(105.0), 1e-15);
    // The horizon (90 deg from the apex) is at r = 90/105.
    const auto h = fish.direction_to_uv({0, 0, -1});
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->y, -90.0 / 105.0, 1e-12);
    // The rim is 15 deg below the horizon, in front.
    expect_vec_near(*fish.uv_to_direction({0, -1}), {0, -std::sin(glm::radians(15.0)), -std::cos(glm::radians(15.0))},
                    1e-12);
    // 100 deg from the apex is inside, 110 deg is beyond the fov, the nadir far outside.
    EXPECT_TRUE(fish.direction_to_uv({std::sin(glm::radians(100.0)), std::cos(glm::radians(100.0)), 0}));
    EXPECT_FALSE(fish.direction_to_uv({std::sin(glm::radians(110.0)), std::cos(glm::radians(110.0)), 0}));
    EXPECT_FALSE(fish.direction_to_uv({0, -1, 0}));
}

TEST(Fisheye, OutsideTheCircle) {
    const FisheyeMapping fish(180.0);
    EXPECT_FALSE(fish.uv_to_direction({1.0001, 0}));
    EXPECT_FALSE(fish.uv_to_direction({0.8, 0.8}));  // image corner region
    EXPECT_FALSE(fish.uv_to_direction({-1, -1}));
    EXPECT_TRUE(fish.uv_to_direction({0.7, 0.7}));  // r = 0.99
    EXPECT_TRUE(fish.uv_to_direction({0, 1}));      // on the rim
    // Below the horizon is outside a 180 deg dome.
    EXPECT_FALSE(fish.direction_to_uv({0, -0.1, -1}));
    EXPECT_FALSE(fish.direction_to_uv({0, -1, 0}));
    // Pixel corners of the domemaster are outside.
    EXPECT_FALSE(fish.uv_to_direction(FisheyeMapping::pixel_to_uv({0.5, 0.5}, 256)));
}

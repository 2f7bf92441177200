// Analytic visibility of the glare source (common/glare/analytic_visibility): the visible fraction
// (the disc-overlap math of the eclipse shadows, area-weighted) and the visible centroid's offset, against
// a brute-force double reference written here: rays from the camera on a fine polar grid over the
// source's apparent disc (solid-angle weights), each tested against every occluder sphere in
// double (hit in front of the camera and before the source's surface), accumulating the visible
// solid angle and its first moment in the tangent plane (angle times direction, radians).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "config/scene_config.hpp"
#include "eclipse/eclipse_reference.hpp"
#include "glare/analytic_visibility.hpp"
#include "shading/shared_shading.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kAu = 1.495978707e11;
constexpr double kSunRadius = 6.957e8;
constexpr double kEarthRadius = 6.371e6;
constexpr double kMoonDistance = 3.844e8;

struct Brute {
    double fraction = 1.0;
    glm::dvec3 offset{0.0};
};

// Any two unit vectors perpendicular to u and to each other.
void basis(const glm::dvec3& u, glm::dvec3& e1, glm::dvec3& e2) {
    const glm::dvec3 helper = std::fabs(u.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    e1 = glm::normalize(glm::cross(u, helper));
    e2 = glm::cross(u, e1);
}

// Ray (origin o, unit direction v) against a sphere: the entry and exit distances, false on a miss.
bool ray_sphere(const glm::dvec3& o, const glm::dvec3& v, const glm::dvec3& center, double r, double& t0, double& t1) {
    const glm::dvec3 oc = o - center;
    const double len = glm::length(oc);
    const double b = glm::dot(oc, v);
    const double c = (len - r) * (len + r);  // no cancellation of |oc|^2 - r^2 for grazing rays
    const double disc = b * b - c;
    if (disc < 0.0) return false;
    const double q = std::sqrt(disc);
    t0 = -b - q;
    t1 = -b + q;
    return true;
}

Brute brute_force(const glm::dvec3& camera, const glm::dvec3& source, double source_r,
                  const std::vector<SphereOccluder>& occluders, int rings = 500, int spokes = 2000) {
    const glm::dvec3 to_source = source - camera;
    const double ds = glm::length(to_source);
    const glm::dvec3 us = to_source / ds;
    glm::dvec3 e1, e2;
    basis(us, e1, e2);
    const double sigma = std::asin(source_r / ds);
    const double dpsi = sigma / rings, dphi = 2.0 * kPi / spokes;
    std::vector<glm::dvec2> ring_dirs(spokes);
    for (int j = 0; j < spokes; ++j) ring_dirs[j] = {std::cos((j + 0.5) * dphi), std::sin((j + 0.5) * dphi)};
    double total = 0.0, visible = 0.0;
    glm::dvec3 moment(0.0);
    for (int i = 0; i < rings; ++i) {
        const double psi = (i + 0.5) * dpsi;
        const double w = std::sin(psi) * dpsi * dphi;  // solid angle of the cell
        for (int j = 0; j < spokes; ++j) {
            const glm::dvec3 side = ring_dirs[j].x * e1 + ring_dirs[j].y * e2;
            const glm::dvec3 v = std::cos(psi) * us + std::sin(psi) * side;
            double s0 = 0.0, s1 = 0.0;
            ray_sphere(camera, v, source, source_r, s0, s1);  // inside the apparent disc: always hits
            bool blocked = false;
            for (const SphereOccluder& o : occluders) {
                double t0 = 0.0, t1 = 0.0;
                if (ray_sphere(camera, v, o.center_m, o.radius_m, t0, t1) && t1 > 0.0 && t0 < s0) {
                    blocked = true;
                    break;
                }
            }
            total += w;
            if (!blocked) {
                visible += w;
                moment += (w * psi) * side;
            }
        }
    }
    Brute b;
    b.fraction = visible / total;
    b.offset = visible > 0.0 ? moment / visible : glm::dvec3(0.0);
    return b;
}

// A sunlit scene in world coordinates: Sun at the origin, camera near the Earth's orbit.
struct Sky {
    glm::dvec3 camera{1.38e11, 4.9e10, 2.1e10};
    glm::dvec3 sun{0.0};
    double sun_r = kSunRadius;
    glm::dvec3 us() const { return glm::normalize(sun - camera); }
    double sigma() const { return std::asin(sun_r / glm::length(sun - camera)); }
    // A unit vector perpendicular to the Sun's direction (the side the occluder sits on).
    glm::dvec3 side() const {
        glm::dvec3 e1, e2;
        basis(us(), e1, e2);
        return glm::normalize(0.6 * e1 + 0.8 * e2);
    }
    // An occluder at distance dist, angle theta from the Sun's centre toward side(), apparent radius rho.
    SphereOccluder occluder(double theta, double rho, double dist = kMoonDistance) const {
        const glm::dvec3 dir = std::cos(theta) * us() + std::sin(theta) * side();
        return {camera + dist * dir, dist * std::sin(rho)};
    }
    GlareVisibility analytic(const std::vector<SphereOccluder>& occ) const {
        return analytic_visibility(camera, sun, sun_r, occ);
    }
    Brute brute(const std::vector<SphereOccluder>& occ, int rings = 500, int spokes = 2000) const {
        return brute_force(camera, sun, sun_r, occ, rings, spokes);
    }
};

// The visible fraction of a unit disc cut by a straight edge at signed distance h from its centre
// (h > 0: the centre is visible): the a -> infinity limit of the disc-overlap fraction.
double straight_edge_fraction(double h) {
    if (h >= 1.0) return 1.0;
    if (h <= -1.0) return 0.0;
    const double alpha = std::acos(h);
    return 1.0 - (alpha - h * std::sqrt(1.0 - h * h)) / kPi;
}

void expect_zero(const glm::dvec3& v) {
    EXPECT_EQ(v.x, 0.0);
    EXPECT_EQ(v.y, 0.0);
    EXPECT_EQ(v.z, 0.0);
}

// The analytic offset against the brute force's: same direction, magnitude within rel.
void expect_offset_near(const glm::dvec3& analytic, const glm::dvec3& brute, double rel) {
    const double mb = glm::length(brute);
    ASSERT_GT(mb, 0.0);
    EXPECT_NEAR(glm::length(analytic), mb, rel * mb);
    EXPECT_LT(glm::length(analytic - brute), rel * mb) << "direction differs";
}

}  // namespace

TEST(GlareVisibility, UnoccludedIsFullAndCentred) {
    const Sky sky;
    const double sigma = sky.sigma();
    const glm::dvec3 us = sky.us();
    // Nothing at all.
    {
        const GlareVisibility v = sky.analytic({});
        EXPECT_EQ(v.visible_fraction, 1.0);
        expect_zero(v.centroid_offset);
    }
    // Beside the disc (apart by 1 % of its radius): no overlap.
    {
        const GlareVisibility v = sky.analytic({sky.occluder(2.01 * sigma, sigma)});
        EXPECT_EQ(v.visible_fraction, 1.0);
        expect_zero(v.centroid_offset);
    }
    // Behind the source, 2 AU away: centred on the line of sight and apparently 3x the Sun, or
    // off-centre where, in front, it would hide part of the disc (a lens: a centroid offset).
    for (const SphereOccluder& far : {SphereOccluder{sky.camera + 2.0 * kAu * us, 2.0 * kAu * std::sin(3.0 * sigma)},
                                      sky.occluder(2.0 * sigma, 1.5 * sigma, 2.0 * kAu)}) {
        EXPECT_EQ(sky.brute({far}, 100, 400).fraction, 1.0);  // the reference agrees: not in front
        const GlareVisibility v = sky.analytic({far});
        EXPECT_EQ(v.visible_fraction, 1.0);
        expect_zero(v.centroid_offset);
    }
    // Behind the camera: on the line of sight the other way, at the Moon's distance, huge.
    {
        const SphereOccluder behind{sky.camera - kMoonDistance * us, kMoonDistance * std::sin(0.5)};
        EXPECT_EQ(sky.brute({behind}, 100, 400).fraction, 1.0);
        const GlareVisibility v = sky.analytic({behind});
        EXPECT_EQ(v.visible_fraction, 1.0);
        expect_zero(v.centroid_offset);
    }
}

TEST(GlareVisibility, HalfCoveredMatchesBruteForce) {
    // A Moon-like occluder three times the Sun's apparent radius, its edge through the Sun's centre.
    const Sky sky;
    const double sigma = sky.sigma();
    const std::vector<SphereOccluder> occ{sky.occluder(3.0 * sigma, 3.0 * sigma)};
    const GlareVisibility v = sky.analytic(occ);
    const Brute b = sky.brute(occ);
    EXPECT_GT(v.visible_fraction, 0.5);  // the occluder's edge bulges away from the centre:
    EXPECT_LT(v.visible_fraction, 0.6);  // a little less than half is hidden
    EXPECT_NEAR(v.visible_fraction, b.fraction, 0.005 * b.fraction);
    // Away from the occluder, perpendicular to the Sun's direction, as large as the reference's.
    EXPECT_LT(glm::dot(v.centroid_offset, sky.side()), 0.0);
    EXPECT_NEAR(glm::dot(v.centroid_offset, sky.us()), 0.0, 1e-12 * sigma);
    expect_offset_near(v.centroid_offset, b.offset, 0.02);
    // Of the right size: a half disc's centroid lies 4 / (3 pi) radii from the centre.
    EXPECT_GT(glm::length(v.centroid_offset), 0.3 * sigma);
    EXPECT_LT(glm::length(v.centroid_offset), 0.6 * sigma);
}

TEST(GlareVisibility, SweepAcrossTheDiscIsMonotoneAndMatchesBruteForce) {
    const Sky sky;
    const double sigma = sky.sigma();
    const double a = 1.05;
    double previous = 1.0;
    for (int k = 22; k >= 0; --k) {
        const double s = 0.1 * k;  // 2.2 (apart) .. 0 (centred, total)
        SCOPED_TRACE("s = " + std::to_string(s));
        const std::vector<SphereOccluder> occ{sky.occluder(s * sigma, a * sigma)};
        const GlareVisibility v = sky.analytic(occ);
        const Brute b = sky.brute(occ, 400, 1600);
        // Non-increasing as the discs close (float evaluation: allow its rounding, 3e-7).
        EXPECT_LE(v.visible_fraction, previous + 3e-7);
        previous = v.visible_fraction;
        EXPECT_NEAR(v.visible_fraction, b.fraction, 0.005);
        if (s <= a - 1.0) {  // totality
            EXPECT_EQ(v.visible_fraction, 0.0);
            expect_zero(v.centroid_offset);
        } else if (s >= 1.0 + a) {
            EXPECT_EQ(v.visible_fraction, 1.0);
            expect_zero(v.centroid_offset);
        } else {
            EXPECT_LT(glm::dot(v.centroid_offset, sky.side()), 0.0);
            // Thin crescents near totality are coarse in the grid: offsets compared where the
            // visible part is several cells thick.
            if (b.fraction > 0.05) expect_offset_near(v.centroid_offset, b.offset, 0.02);
        }
    }
}

TEST(GlareVisibility, AnnularSmallOccluderInside) {
    const Sky sky;
    const double sigma = sky.sigma();
    const double a = 0.3;
    // Centred: 1 - a^2, no offset to speak of.
    {
        const GlareVisibility v = sky.analytic({sky.occluder(0.0, a * sigma)});
        EXPECT_NEAR(v.visible_fraction, 1.0 - a * a, 1e-4);
        EXPECT_LT(glm::length(v.centroid_offset), 1e-9 * sigma);
    }
    // Off-centre but inside (s = 0.4 < 1 - a): same fraction; the centroid moves away from the hole
    // by a^2 s / (1 - a^2) (moment balance of the disc minus the hole).
    {
        const double s = 0.4;
        const std::vector<SphereOccluder> occ{sky.occluder(s * sigma, a * sigma)};
        const GlareVisibility v = sky.analytic(occ);
        EXPECT_NEAR(v.visible_fraction, 1.0 - a * a, 1e-4);
        EXPECT_LT(glm::dot(v.centroid_offset, sky.side()), 0.0);
        EXPECT_NEAR(glm::length(v.centroid_offset), a * a * s / (1.0 - a * a) * sigma, 1e-3 * a * a * s * sigma);
        const Brute b = sky.brute(occ);
        EXPECT_NEAR(v.visible_fraction, b.fraction, 0.005);
        expect_offset_near(v.centroid_offset, b.offset, 0.02);
    }
}

TEST(GlareVisibility, TwoOccludersMultiplyAndTheirMomentsAdd) {
    // Two small holes on opposite-ish sides of the disc, not overlapping.
    const Sky sky;
    const double sigma = sky.sigma();
    const SphereOccluder one = sky.occluder(0.5 * sigma, 0.2 * sigma);
    glm::dvec3 e1, e2;
    basis(sky.us(), e1, e2);
    const glm::dvec3 dir2 = std::cos(0.4 * sigma) * sky.us() - std::sin(0.4 * sigma) * e1;
    const SphereOccluder two{sky.camera + 1e9 * dir2, 1e9 * std::sin(0.25 * sigma)};
    const GlareVisibility v1 = sky.analytic({one}), v2 = sky.analytic({two}), v = sky.analytic({one, two});
    EXPECT_DOUBLE_EQ(v.visible_fraction, v1.visible_fraction * v2.visible_fraction);
    const Brute b = sky.brute({one, two});
    EXPECT_NEAR(v.visible_fraction, b.fraction, 0.005);  // product vs. area sum: 0.2^2 0.25^2 apart
    expect_offset_near(v.centroid_offset, b.offset, 0.02);
}

TEST(GlareVisibility, EclipseExactTendsToTheStraightEdgeAtHugeRatio) {
    // The straight-edge limit that the huge-occluder regime uses is what the shared exact
    // function gives at a = 20000 (with s = a + h exact in float), and what the reference gives.
    const float a = 20000.0f;
    for (int k = -70; k <= 70; ++k) {
        const double h = k / 64.0;
        SCOPED_TRACE("h = " + std::to_string(h));
        const double edge = straight_edge_fraction(h);
        EXPECT_NEAR(sh::eclipse_visible_exact(a, a + static_cast<float>(h), 0.0f), edge, 2e-5);
        EXPECT_NEAR(eclipse::visible_fraction_reference(a, a + h, 0.0), edge, 1e-5);
    }
}

TEST(GlareVisibility, GroundObserverSunOnTheHorizon) {
    // Camera 2 m above an Earth-sized sphere, the Sun at 1 AU along the geometric horizon (the
    // tangent from the camera to the sphere, dip acos(R / (R + 2 m)) below the horizontal).
    const double height = 2.0;
    const glm::dvec3 earth{kAu, -3.0e9, 1.0e9};
    const glm::dvec3 up = glm::normalize(glm::dvec3(0.3, 0.5, 0.81));
    glm::dvec3 e1, e2;
    basis(up, e1, e2);
    const glm::dvec3 camera = earth + (kEarthRadius + height) * up;
    const double dip = std::acos(kEarthRadius / (kEarthRadius + height));
    const std::vector<SphereOccluder> ground{{earth, kEarthRadius}};
    const auto sun_at = [&](double elevation) {
        return camera + kAu * (std::cos(elevation) * e1 + std::sin(elevation) * up);
    };

    const glm::dvec3 sun = sun_at(-dip);
    const GlareVisibility v = analytic_visibility(camera, sun, kSunRadius, ground);
    const Brute b = brute_force(camera, sun, kSunRadius, ground);
    EXPECT_NEAR(v.visible_fraction, 0.5, 0.01);
    EXPECT_NEAR(v.visible_fraction, b.fraction, 0.02 * b.fraction);
    EXPECT_GT(glm::dot(v.centroid_offset, up), 0.0);  // the upper half is what shows
    expect_offset_near(v.centroid_offset, b.offset, 0.02);

    EXPECT_EQ(analytic_visibility(camera, sun_at(-dip + 1.0 * kDeg), kSunRadius, ground).visible_fraction, 1.0);
    const GlareVisibility set = analytic_visibility(camera, sun_at(-dip - 1.0 * kDeg), kSunRadius, ground);
    EXPECT_EQ(set.visible_fraction, 0.0);
    expect_zero(set.centroid_offset);
}

TEST(GlareVisibility, GroundObserverNearTheHorizonMatchesBruteForce) {
    // Sunrise seen from 2 m: elevations across the whole partial range, including the band between
    // the geometric horizon and the astronomical one (centre above the horizontal, lower limb
    // still below the dip) where the ground's centre lies more than 90 degrees from the Sun.
    const double height = 2.0;
    const glm::dvec3 earth{-4.0e10, kAu, 2.0e9};
    const glm::dvec3 up = glm::normalize(glm::dvec3(-0.7, 0.1, 0.7));
    glm::dvec3 e1, e2;
    basis(up, e1, e2);
    const glm::dvec3 camera = earth + (kEarthRadius + height) * up;
    const double dip = std::acos(kEarthRadius / (kEarthRadius + height));
    const std::vector<SphereOccluder> ground{{earth, kEarthRadius}};
    const double sigma = std::asin(kSunRadius / kAu);
    double previous = 0.0;
    for (int k = -12; k <= 12; ++k) {
        const double elevation = -dip + k * 0.1 * sigma;
        SCOPED_TRACE("elevation (deg) = " + std::to_string(elevation / kDeg));
        const glm::dvec3 sun = camera + kAu * (std::cos(elevation) * e1 + std::sin(elevation) * up);
        const GlareVisibility v = analytic_visibility(camera, sun, kSunRadius, ground);
        const Brute b = brute_force(camera, sun, kSunRadius, ground, 300, 1200);
        EXPECT_NEAR(v.visible_fraction, b.fraction, 0.005);
        // The straight edge at the ideal dip; the positions themselves are only kept to ~20 um at
        // 1 AU from the origin, which moves the 2 m camera's limb by ~3e-9 rad.
        EXPECT_NEAR(v.visible_fraction, straight_edge_fraction((elevation + dip) / sigma), 1e-6);
        EXPECT_GE(v.visible_fraction, previous);  // rising Sun
        previous = v.visible_fraction;
        if (b.fraction > 0.05 && b.fraction < 1.0) expect_offset_near(v.centroid_offset, b.offset, 0.02);
    }
}

TEST(GlareVisibility, LensAndStraightEdgeRegimesMeetAtTheThreshold) {
    // Occluders of apparent radius just below and just above kStraightEdgeAngle (the lens from the
    // eclipse functions, then the straight edge): both agree with the brute force and each other.
    const Sky sky;
    const double sigma = sky.sigma();
    const double dist = 2.0e7;
    for (double h : {-0.6, 0.0, 0.5}) {
        SCOPED_TRACE("h = " + std::to_string(h));
        double fractions[2] = {0.0, 0.0};
        for (int side = 0; side < 2; ++side) {
            const double rho = kStraightEdgeAngle + (side == 0 ? -1e-4 : 1e-4);
            const std::vector<SphereOccluder> occ{sky.occluder(rho + h * sigma, rho, dist)};
            const GlareVisibility v = sky.analytic(occ);
            // Fine in angle: at h = 0 the edge runs nearly radially across the grid, and its true
            // bend (a few 1e-3 rad at the rim) has to be resolved by the spokes.
            const Brute b = sky.brute(occ, 150, 40000);
            EXPECT_NEAR(v.visible_fraction, b.fraction, 5e-4);  // the models' curvature error, ~2.5e-4
            expect_offset_near(v.centroid_offset, b.offset, 0.02);
            fractions[side] = v.visible_fraction;
        }
        EXPECT_NEAR(fractions[0], fractions[1], 1e-3);
    }
}

TEST(GlareVisibility, CameraInsideAnOccluderSeesNothing) {
    const Sky sky;
    // Inside a small sphere around the camera, and also with a far-off clear occluder listed first.
    const std::vector<SphereOccluder> occ{sky.occluder(0.3, 1e-3), {sky.camera + glm::dvec3(3.0, -2.0, 1.0), 10.0}};
    const GlareVisibility v = sky.analytic(occ);
    EXPECT_EQ(v.visible_fraction, 0.0);
    expect_zero(v.centroid_offset);
    EXPECT_EQ(sky.brute(occ, 50, 200).fraction, 0.0);
    // Inside a planet, Sun overhead.
    const glm::dvec3 earth = sky.camera + glm::dvec3(1.0e6, 2.0e6, -3.0e6);
    const GlareVisibility inside = sky.analytic({{earth, kEarthRadius}});
    EXPECT_EQ(inside.visible_fraction, 0.0);
    expect_zero(inside.centroid_offset);
}

TEST(GlareVisibility, SnapshotOccludersSkipStarsAndTheSource) {
    SceneConfig scene;
    const auto add = [&](const char* name, BodyKind kind, double radius) {
        BodyConfig b;
        b.id = static_cast<uint16_t>(scene.bodies.size());
        b.name = name;
        b.kind = kind;
        b.radius_m = radius;
        scene.bodies.push_back(b);
    };
    add("sun", BodyKind::Star, kSunRadius);
    add("earth", BodyKind::Planet, kEarthRadius);
    add("moon", BodyKind::Moon, 1.7374e6);
    add("companion", BodyKind::Star, 2.0e8);
    add("mars", BodyKind::Planet, 3.3895e6);

    Snapshot snap;
    snap.camera_position_m = {kAu, 0.0, 1.0e7};
    snap.bodies = {{0, {0.0, 0.0, 0.0}},
                   {1, {kAu, 0.0, 0.0}},
                   {2, {kAu, kMoonDistance, 0.0}},
                   {3, {-1e12, 0.0, 0.0}},
                   {4, {0.0, 2.2e11, 0.0}}};

    const std::vector<SphereOccluder> from_sun = snapshot_occluders(snap, scene, 0);
    ASSERT_EQ(from_sun.size(), 3u);
    EXPECT_EQ(from_sun[0].center_m, snap.bodies[1].position_m);
    EXPECT_EQ(from_sun[0].radius_m, kEarthRadius);
    EXPECT_EQ(from_sun[1].center_m, snap.bodies[2].position_m);
    EXPECT_EQ(from_sun[1].radius_m, 1.7374e6);
    EXPECT_EQ(from_sun[2].center_m, snap.bodies[4].position_m);
    EXPECT_EQ(from_sun[2].radius_m, 3.3895e6);

    // With the Moon as the source: the Earth and Mars, neither star nor the Moon itself.
    const std::vector<SphereOccluder> from_moon = snapshot_occluders(snap, scene, 2);
    ASSERT_EQ(from_moon.size(), 2u);
    EXPECT_EQ(from_moon[0].radius_m, kEarthRadius);
    EXPECT_EQ(from_moon[1].radius_m, 3.3895e6);

    // Used directly: from 10 000 km above the Earth's pole (as seen here) the Earth and the Moon
    // lie 90 degrees from the Sun, so it shows whole.
    const GlareVisibility v =
        analytic_visibility(snap.camera_position_m, snap.bodies[0].position_m, kSunRadius, from_sun);
    EXPECT_EQ(v.visible_fraction, 1.0);
}

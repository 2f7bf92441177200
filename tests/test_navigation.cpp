// The navigation model for flying the dome with a 3D mouse or gamepad: input shaping (dead zone,
// response curve, smoothing, unplugging), the three modes (orbit, free fly, surface walk), go-to
// flights and precision at astronomical distances. Deterministic: fixed bodies and seeded noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "config/scene_config.hpp"
#include "navigation/input_shaper.hpp"
#include "navigation/nav_body.hpp"
#include "navigation/navigation_model.hpp"

using namespace cupola;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kAU = 1.495978707e11;
constexpr double kSunR = 6.957e8, kEarthR = 6.371e6, kMoonR = 1.7374e6;
const glm::dvec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

// Sun at the origin, the Earth 1 AU away along x (tilted, turned), the Moon 384 400 km beyond it.
std::vector<NavBody> solar_system(double earth_spin_rad = 0.3) {
    const glm::dquat tilt = glm::angleAxis(glm::radians(23.44), kX);
    const glm::dvec3 earth(kAU, 0.0, 0.0);
    return {
        {0, "sun", kSunR, glm::dvec3(0.0), glm::dquat(1, 0, 0, 0)},
        {1, "earth", kEarthR, earth, tilt * glm::angleAxis(earth_spin_rad, kZ)},
        {2, "moon", kMoonR, earth + glm::dvec3(3.844e8, 0.0, 0.0), glm::angleAxis(kPi, kZ)},
    };
}

const NavBody& body(const std::vector<NavBody>& bodies, uint16_t id) {
    for (const auto& b : bodies)
        if (b.id == id) return b;
    throw std::runtime_error("no body");
}

// Camera -> world rotation looking along `fwd` with `up` as near the top of the picture as it goes.
glm::dquat look(glm::dvec3 fwd, glm::dvec3 up) {
    fwd = glm::normalize(fwd);
    const glm::dvec3 right = glm::normalize(glm::cross(fwd, up));
    return glm::normalize(glm::quat_cast(glm::dmat3(right, glm::cross(right, fwd), -fwd)));
}

glm::dvec3 forward_of(const glm::dquat& q) { return q * glm::dvec3(0, 0, -1); }
glm::dvec3 up_of(const glm::dquat& q) { return q * kY; }
glm::dvec3 right_of(const glm::dquat& q) { return q * kX; }

bool finite(const CameraPose& p) {
    return std::isfinite(p.position_m.x) && std::isfinite(p.position_m.y) && std::isfinite(p.position_m.z) &&
           std::isfinite(p.orientation.w) && std::isfinite(p.orientation.x) && std::isfinite(p.orientation.y) &&
           std::isfinite(p.orientation.z);
}

bool bit_identical(const CameraPose& a, const CameraPose& b) {
    return std::memcmp(&a.position_m, &b.position_m, sizeof a.position_m) == 0 &&
           std::memcmp(&a.orientation, &b.orientation, sizeof a.orientation) == 0;
}

NavSample sample(const NavAxes& a) {
    NavSample s;
    s.axes = a;
    s.connected = true;
    return s;
}

// A point `alt` above a body's surface along the world direction `dir`.
glm::dvec3 above(const NavBody& b, glm::dvec3 dir, double alt) {
    return b.position_m + glm::normalize(dir) * (b.radius_m + alt);
}

}  // namespace

// ---- input shaping -----------------------------------------------------------------------------

TEST(NavInputShaper, DeadZoneGivesExactZeroAndNoDrift) {
    const auto bodies = solar_system();
    const NavBody& earth = body(bodies, 1);
    InputShaper shaper;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(-0.0799, 0.0799);  // inside the 0.08 dead zone

    // One model per mode, all at rest near the Earth.
    NavigationModel fly, orbit, walk;
    const CameraPose start{above(earth, glm::dvec3(1, 2, 3), 2.0e6), look(glm::dvec3(0, 1, 0), kZ)};
    for (NavigationModel* m : {&fly, &orbit, &walk}) m->set_pose(start, bodies);
    orbit.set_mode(NavMode::Orbit, bodies);
    walk.set_mode(NavMode::SurfaceWalk, bodies);
    const CameraPose p_fly = fly.pose(bodies), p_orbit = orbit.pose(bodies), p_walk = walk.pose(bodies);

    for (int i = 0; i < 10000; ++i) {
        NavAxes raw{noise(rng), noise(rng), noise(rng), noise(rng), noise(rng), noise(rng)};
        const NavAxes out = shaper.shape(sample(raw), 1.0 / 60.0);
        ASSERT_EQ(out, NavAxes{}) << "step " << i;
        fly.step(out, 1.0 / 60.0, bodies);
        orbit.step(out, 1.0 / 60.0, bodies);
        walk.step(out, 1.0 / 60.0, bodies);
    }
    EXPECT_TRUE(bit_identical(fly.pose(bodies), p_fly));
    EXPECT_TRUE(bit_identical(orbit.pose(bodies), p_orbit));
    EXPECT_TRUE(bit_identical(walk.pose(bodies), p_walk));
}

TEST(NavInputShaper, ContinuousAtTheDeadZoneEdgeAndFullAtFullDeflection) {
    for (double exponent : {1.0, 2.0, 3.0}) {
        InputShaper shaper({0.08, 0.0, exponent});  // no smoothing: the curve itself
        auto f = [&](double x) { return shaper.shape(sample({x, 0, 0, 0, 0, 0}), 0.01).right; };
        EXPECT_EQ(f(0.08), 0.0);
        EXPECT_EQ(f(-0.08), 0.0);
        EXPECT_LT(std::abs(f(0.08 + 1e-7)), 2e-7);  // no step at the edge
        EXPECT_LT(std::abs(f(-0.08 - 1e-7)), 2e-7);
        EXPECT_GT(f(0.08 + 1e-3), 0.0);  // (values under 1e-9 snap to 0)
        EXPECT_LT(f(-0.08 - 1e-3), 0.0);
        EXPECT_DOUBLE_EQ(f(1.0), 1.0);
        EXPECT_DOUBLE_EQ(f(-1.0), -1.0);
        EXPECT_DOUBLE_EQ(f(5.0), 1.0);  // clamped
        EXPECT_EQ(f(std::nan("")), 0.0);
        // Monotonic and odd.
        double prev = 0.0;
        for (double x = 0.0; x <= 1.0; x += 0.001) {
            const double y = f(x);
            EXPECT_GE(y, prev);
            EXPECT_DOUBLE_EQ(f(-x), -y);
            prev = y;
        }
        // The curve: ((|x| - dz) / (1 - dz))^exponent.
        EXPECT_NEAR(f(0.54), std::pow(0.5, exponent), 1e-12);
    }
}

TEST(NavInputShaper, SmoothingIsFrameRateIndependent) {
    const NavAxes held{0.6, -0.9, 1.0, 0.3, -0.5, 0.7};
    InputShaper coarse, fine;
    NavAxes a, b;
    for (int i = 0; i < 100; ++i) a = coarse.shape(sample(held), 0.010);
    for (int i = 0; i < 1000; ++i) b = fine.shape(sample(held), 0.001);
    EXPECT_NEAR(a.right, b.right, 1e-12);
    EXPECT_NEAR(a.up, b.up, 1e-12);
    EXPECT_NEAR(a.forward, b.forward, 1e-12);
    EXPECT_NEAR(a.pitch_up, b.pitch_up, 1e-12);
    EXPECT_NEAR(a.yaw_left, b.yaw_left, 1e-12);
    EXPECT_NEAR(a.roll_ccw, b.roll_ccw, 1e-12);
    // After 1 s with tau = 0.12 s: 1 - exp(-1/0.12) of the way to the curve's value.
    const double k = 1.0 - std::exp(-1.0 / 0.12);
    EXPECT_NEAR(a.forward, k * 1.0, 1e-12);
    EXPECT_NEAR(a.right, k * std::pow((0.6 - 0.08) / 0.92, 2.0), 1e-12);

    // After release the output decays and then snaps to exactly zero.
    for (int i = 0; i < 2000; ++i) a = coarse.shape(sample({}), 0.010);
    EXPECT_EQ(a, NavAxes{});
    // Zero dt changes nothing.
    InputShaper s;
    s.shape(sample(held), 0.05);
    const NavAxes before = s.shape(sample(held), 0.0);
    EXPECT_EQ(s.shape(sample({}), 0.0), before);
}

TEST(NavInputShaper, UnplugGivesZeroAtOnceAndTheCameraStopsNextStep) {
    const auto bodies = solar_system();
    NavigationModel model;
    model.set_pose({above(body(bodies, 1), kY, 1.0e6), look(kX, kZ)}, bodies);
    InputShaper shaper;
    const NavAxes push{0.5, 0.2, 1.0, 0.4, 0.3, 0.2};
    CameraPose last;
    for (int i = 0; i < 60; ++i) last = model.step(shaper.shape(sample(push), 1.0 / 60.0), 1.0 / 60.0, bodies);

    NavSample unplugged = sample(push);  // stale axes must not count
    unplugged.connected = false;
    const NavAxes out = shaper.shape(unplugged, 1.0 / 60.0);
    EXPECT_EQ(out, NavAxes{});
    const CameraPose stopped = model.step(out, 1.0 / 60.0, bodies);
    EXPECT_TRUE(bit_identical(stopped, last));
    // Plugged back in at rest: no smoothing tail from before the unplug.
    EXPECT_EQ(shaper.shape(sample({}), 1.0 / 60.0), NavAxes{});
    EXPECT_TRUE(bit_identical(model.step(NavAxes{}, 1.0 / 60.0, bodies), last));
}

// ---- orbit -------------------------------------------------------------------------------------

TEST(NavOrbit, KeepsTheDistanceAndLooksAtTheTargetWhileItMoves) {
    auto bodies = solar_system();
    NavigationModel model;
    model.set_pose({above(body(bodies, 1), glm::dvec3(0.3, -1, 0.4), 3.0 * kEarthR), look(kX, kZ)}, bodies);
    model.set_mode(NavMode::Orbit, bodies);
    ASSERT_EQ(model.anchor(), 1);
    const double d0 = glm::length(model.offset_m(bodies));
    EXPECT_NEAR(d0, 4.0 * kEarthR, 1e-3);

    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const glm::dvec3 velocity(-1.0e3, 2.9e4, 1.2e4);  // m/s, roughly the Earth's orbital speed
    for (int i = 0; i < 10000; ++i) {
        const double dt = 1.0 / 60.0;
        NavAxes in{u(rng), u(rng), 0.0, u(rng), u(rng), u(rng)};
        for (auto& b : bodies) b.position_m += velocity * dt * (b.id == 0 ? 0.0 : 1.0);
        bodies[1].orientation = glm::normalize(glm::angleAxis(7.3e-5 * dt, kZ) * bodies[1].orientation);
        const CameraPose p = model.step(in, dt, bodies);
        const glm::dvec3 off = model.offset_m(bodies);
        ASSERT_NEAR(glm::length(off) / d0 - 1.0, 0.0, 1e-9) << "step " << i;
        const glm::dvec3 to_centre = body(bodies, 1).position_m - p.position_m;
        ASSERT_NEAR(glm::length(to_centre) / d0 - 1.0, 0.0, 1e-9) << "step " << i;
        ASSERT_GT(glm::dot(glm::normalize(to_centre), forward_of(p.orientation)), 1.0 - 1e-12) << "step " << i;
    }
    EXPECT_EQ(model.mode(), NavMode::Orbit);
}

TEST(NavOrbit, YawSwingsAroundTheCentreAtTheOrbitRate) {
    const auto bodies = solar_system();
    NavigationModel model;
    model.set_pose({above(body(bodies, 1), kY, 3.0 * kEarthR), look(-kY, kZ)}, bodies);
    model.set_mode(NavMode::Orbit, bodies);
    const glm::dvec3 before = glm::normalize(model.offset_m(bodies));
    for (int i = 0; i < 60; ++i) model.step({0, 0, 0, 0, 1.0, 0}, 1.0 / 60.0, bodies);  // 1 s full yaw
    const glm::dvec3 after = glm::normalize(model.offset_m(bodies));
    EXPECT_NEAR(std::acos(std::clamp(glm::dot(before, after), -1.0, 1.0)), glm::radians(30.0), 1e-9);
    // Translation right swings the same way as yaw left; up opposite to pitch up.
    NavigationModel a = model, b = model;
    a.step({1.0, 0, 0, 0, 0, 0}, 0.1, bodies);
    b.step({0, 0, 0, 0, 1.0, 0}, 0.1, bodies);
    EXPECT_NEAR(glm::length(a.offset_m(bodies) - b.offset_m(bodies)), 0.0, 1e-6);
    a = model, b = model;
    a.step({0, 1.0, 0, 0, 0, 0}, 0.1, bodies);
    b.step({0, 0, 0, -1.0, 0, 0}, 0.1, bodies);
    EXPECT_NEAR(glm::length(a.offset_m(bodies) - b.offset_m(bodies)), 0.0, 1e-6);
    // The camera moved right when swinging right.
    const glm::dvec3 right = right_of(model.pose(bodies).orientation);
    a = model;
    a.step({1.0, 0, 0, 0, 0, 0}, 0.1, bodies);
    EXPECT_GT(glm::dot(a.offset_m(bodies) - model.offset_m(bodies), right), 0.0);
}

TEST(NavOrbit, ForwardZoomsByTheAltitudeFactorAndStopsAtMinAltitude) {
    const auto bodies = solar_system();
    NavigationModel model;
    model.set_pose({above(body(bodies, 1), kZ, 1.0e7), look(-kZ, kY)}, bodies);
    model.set_mode(NavMode::Orbit, bodies);
    for (int i = 0; i < 100; ++i) model.step({0, 0, 1.0, 0, 0, 0}, 0.01, bodies);
    EXPECT_NEAR(model.altitude_m(bodies) / (1.0e7 * std::exp(-0.5)) - 1.0, 0.0, 1e-9);
    for (int i = 0; i < 100; ++i) model.step({0, 0, -1.0, 0, 0, 0}, 0.01, bodies);
    EXPECT_NEAR(model.altitude_m(bodies) / 1.0e7 - 1.0, 0.0, 1e-9);
    for (int i = 0; i < 1000; ++i) model.step({0, 0, 1.0, 0, 0, 0}, 0.1, bodies);
    EXPECT_NEAR(model.altitude_m(bodies), 1.5, 1e-6);
    model.step({0, 0, 1.0, 0, 0, 0}, 1e9, bodies);  // huge dt
    EXPECT_NEAR(model.altitude_m(bodies), 1.5, 1e-6);
    EXPECT_TRUE(finite(model.step({0, 0, -1.0, 0, 0, 0}, 1e9, bodies)));
}

// ---- free fly ----------------------------------------------------------------------------------

TEST(NavFreeFly, SpeedScalesWithAltitudeFromTheSurfaceToSolarSystemScale) {
    const auto bodies = solar_system();
    const NavBody& earth = body(bodies, 1);
    const NavBody& sun = body(bodies, 0);
    // Horizontal flight at various altitudes; one short step measures the speed.
    auto speed = [&](const glm::dvec3& pos, const glm::dvec3& fwd) {
        NavigationModel m;
        m.set_pose({pos, look(fwd, kZ)}, bodies);
        const glm::dvec3 before = m.offset_m(bodies);
        const double dt = 0.1;
        m.step({0, 0, 1.0, 0, 0, 0}, dt, bodies);
        return glm::length(m.offset_m(bodies) - before) / dt;
    };
    EXPECT_NEAR(speed(above(earth, kY, 10.0), kX), 5.0, 1e-6);  // 0.5 x 10 m per second
    EXPECT_NEAR(speed(above(earth, kY, 1.6), kX), 1.0, 1e-6);   // the walking-pace floor
    const double s10 = speed(above(earth, kY, 10.0), kX);
    const double s10k = speed(above(earth, kY, 1.0e4), kX);
    EXPECT_NEAR(s10k / s10 / 1000.0, 1.0, 1e-7);
    const double s1e8 = speed(above(sun, kZ, 1.0e8), kX);
    const double s1e11 = speed(above(sun, kZ, 1.0e11), kX);
    EXPECT_NEAR(s1e11 / s1e8 / 1000.0, 1.0, 1e-7);
    EXPECT_NEAR(s1e11, 0.5e11, 1.0);
    // Partial deflection scales linearly (shaping happens before the model).
    NavigationModel m;
    m.set_pose({above(earth, kY, 1.0e4), look(kX, kZ)}, bodies);
    const glm::dvec3 before = m.offset_m(bodies);
    m.step({0, 0, 0.25, 0, 0, 0}, 1e-3, bodies);
    EXPECT_NEAR(glm::length(m.offset_m(bodies) - before) / 1e-3, 0.25 * 5.0e3, 1e-4);
}

TEST(NavFreeFly, NeverEntersABody) {
    const auto bodies = solar_system();
    const NavBody& earth = body(bodies, 1);
    NavigationModel model;
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.2, 1.0, -0.3));
    model.set_pose({above(earth, dir, 2.0e7), look(-dir, kZ)}, bodies);
    double dt = 1.0 / 60.0, lowest = INFINITY;
    for (int i = 0; i < 10000; ++i) {
        if (i % 1000 == 999) dt = 100.0;  // an occasional huge frame
        // Straight down first, then pressing down while sliding sideways.
        model.step({i < 5000 ? 0.0 : 0.3, i < 5000 ? 0.0 : -0.2, 1.0, 0.0, 0.0, 0.0}, dt, bodies);
        dt = 1.0 / 60.0;
        const double alt = model.altitude_m(bodies);
        ASSERT_GE(alt, 1.5 - 1e-6) << "step " << i;
        lowest = std::min(lowest, alt);
    }
    EXPECT_LT(lowest, 1.5 + 1e-3);  // it did press against the surface (then slid off it)

    // One step long enough to cross the whole planet stops on the near side.
    NavigationModel through;
    through.set_pose({above(earth, kY, 1.0e7), look(-kY, kZ)}, bodies);
    through.step({0, 0, 1.0, 0, 0, 0}, 10.0, bodies);  // 5e6 m/s x 10 s = 5e7 m
    EXPECT_GE(through.altitude_m(bodies), 1.5 - 1e-6);
    EXPECT_GT(glm::dot(through.offset_m(bodies), kY), 0.0);
    // Starting inside a body lifts the camera out.
    NavigationModel inside;
    inside.set_pose({earth.position_m + glm::dvec3(1.0e6, 0, 0), look(kX, kZ)}, bodies);
    EXPECT_NEAR(inside.altitude_m(bodies), 1.5, 1e-6);
    inside.set_pose({earth.position_m, look(kX, kZ)}, bodies);  // exactly at the centre
    EXPECT_NEAR(inside.altitude_m(bodies), 1.5, 1e-6);
}

TEST(NavFreeFly, ReanchoringKeepsTheWorldPositionContinuous) {
    const auto bodies = solar_system();
    const NavBody& earth = body(bodies, 1);
    const NavBody& moon = body(bodies, 2);
    NavigationModel model;
    // Start near the Earth, flying toward the Moon: halfway the Moon becomes the nearest body.
    const glm::dvec3 start = earth.position_m + glm::dvec3(2.0e7, 3.0e6, -1.0e6);
    const glm::dvec3 fwd = glm::normalize(moon.position_m + glm::dvec3(0, 3.0e6, 0) - start);
    model.set_pose({start, look(fwd, kZ)}, bodies);
    ASSERT_EQ(model.anchor(), 1);
    bool switched = false;
    CameraPose prev = model.pose(bodies);
    for (int i = 0; i < 5000 && !switched; ++i) {
        const double alt = model.altitude_m(bodies);
        const double expected = std::max(1.0, 0.5 * alt) * 0.01;  // forward 1, dt 10 ms
        const glm::dvec3 off_before = model.offset_m(bodies);
        const CameraPose p = model.step({0, 0, 1.0, 0, 0, 0}, 0.01, bodies);
        const glm::dvec3 moved = p.position_m - prev.position_m;
        // World positions round to ~3e-5 m at 1 AU: compare the move to that.
        ASSERT_NEAR(glm::length(moved), expected, 1e-3) << "step " << i;
        ASSERT_GT(glm::dot(glm::normalize(moved), fwd), 1.0 - 1e-9) << "step " << i;
        if (model.anchor() == 2) {
            switched = true;
            // The new offset is the same point seen from the Moon.
            const glm::dvec3 expect_off = off_before + fwd * expected - (moon.position_m - earth.position_m);
            EXPECT_NEAR(glm::length(model.offset_m(bodies) - expect_off), 0.0, 1e-3);
        }
        prev = p;
    }
    EXPECT_TRUE(switched);
}

TEST(NavFreeFly, RidesWithTheAnchorAndRotatesAtTheTurnRate) {
    auto bodies = solar_system();
    NavigationModel model;
    model.set_pose({above(body(bodies, 1), kY, 1.0e5), look(kX, kZ)}, bodies);
    const glm::dvec3 off = model.offset_m(bodies);
    for (auto& b : bodies) b.position_m += glm::dvec3(1.0e6, -2.0e6, 3.0e5);
    const CameraPose p = model.step(NavAxes{}, 0.5, bodies);
    EXPECT_EQ(model.offset_m(bodies), off);
    EXPECT_NEAR(glm::length(p.position_m - (body(bodies, 1).position_m + off)), 0.0, 1e-4);
    // 1 s of full yaw left turns the view 45 degrees to the left.
    const glm::dvec3 f0 = forward_of(p.orientation);
    for (int i = 0; i < 100; ++i) model.step({0, 0, 0, 0, 1.0, 0}, 0.01, bodies);
    const glm::dquat q = model.pose(bodies).orientation;
    EXPECT_NEAR(glm::dot(forward_of(q), f0), std::cos(glm::radians(45.0)), 1e-9);
    EXPECT_GT(glm::dot(glm::cross(f0, forward_of(q)), kZ), 0.0);  // left, with z up
    // pitch_up raises the view; roll_ccw turns the camera right-handed about its +Z (its right
    // axis toward its up axis), like pitch_up and yaw_left about +X and +Y.
    NavigationModel look_up = model, roll = model;
    const CameraPose p0 = model.pose(bodies);
    look_up.step({0, 0, 0, 1.0, 0, 0}, 0.1, bodies);
    EXPECT_GT(glm::dot(forward_of(look_up.pose(bodies).orientation), up_of(p0.orientation)), 0.0);
    roll.step({0, 0, 0, 0, 0, 1.0}, 0.1, bodies);
    EXPECT_GT(glm::dot(right_of(roll.pose(bodies).orientation), up_of(p0.orientation)), 0.0);
    EXPECT_NEAR(glm::dot(forward_of(roll.pose(bodies).orientation), forward_of(p0.orientation)), 1.0, 1e-12);
}

// ---- surface walk ------------------------------------------------------------------------------

namespace {

// Latitude (degrees) of a world offset in a body's frame.
double latitude_deg(const NavBody& b, const glm::dvec3& offset) {
    const glm::dvec3 v = glm::normalize(glm::conjugate(b.orientation) * offset);
    return glm::degrees(std::asin(std::clamp(v.z, -1.0, 1.0)));
}

}  // namespace

TEST(NavSurfaceWalk, StaysAtEyeHeightAcrossThePoleWithTheZenithUp) {
    const auto bodies = solar_system();
    const NavBody& earth = body(bodies, 1);
    // Above 80 N, 30 E, looking north (toward the pole).
    const double lat = glm::radians(80.0), lon = glm::radians(30.0);
    const glm::dvec3 z_body(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
    const glm::dvec3 north_body(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
    const glm::dvec3 zenith = earth.orientation * z_body, north = earth.orientation * north_body;
    NavigationModel model;
    model.set_pose({earth.position_m + zenith * (kEarthR + 5.0e5), look(north - zenith * 0.3, zenith)}, bodies);
    model.set_mode(NavMode::SurfaceWalk, bodies);
    ASSERT_EQ(model.mode(), NavMode::SurfaceWalk);
    EXPECT_NEAR(model.altitude_m(bodies), 1.5, 1e-6);
    EXPECT_NEAR(latitude_deg(earth, model.offset_m(bodies)), 80.0, 1e-9);
    // Heading kept (north), horizon level.
    CameraPose p = model.pose(bodies);
    EXPECT_NEAR(glm::dot(forward_of(p.orientation), north), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(up_of(p.orientation), zenith), 1.0, 1e-12);

    // Walking pace is too slow to reach the pole: raise the eye (the walk speeds up with it),
    // walk 25 degrees north, over the pole, then come back down.
    for (int i = 0; i < 480; ++i) model.step({0, 1.0, 0, 0, 0, 0}, 0.05, bodies);
    const double eye = model.altitude_m(bodies);
    EXPECT_GT(eye, 1.0e5);
    const int walk_steps = int(std::ceil(glm::radians(25.0) * kEarthR / (0.5 * eye * 0.05)));
    double max_lat = -90.0;
    for (int i = 0; i < walk_steps; ++i) {
        p = model.step({0, 0, 1.0, 0, 0, 0}, 0.05, bodies);
        const glm::dvec3 off = model.offset_m(bodies);
        const glm::dvec3 z = glm::normalize(off);
        max_lat = std::max(max_lat, latitude_deg(earth, off));
        ASSERT_NEAR(glm::length(off) - kEarthR, eye, 1e-6) << "step " << i;
        ASSERT_NEAR(glm::dot(up_of(p.orientation), z), 1.0, 1e-12) << "step " << i;
        ASSERT_NEAR(glm::dot(right_of(p.orientation), z), 0.0, 1e-12) << "step " << i;
    }
    EXPECT_GT(max_lat, 89.0);  // went (nearly) over the pole
    const glm::dvec3 v = glm::conjugate(earth.orientation) * model.offset_m(bodies);
    const double lon_now = glm::degrees(std::atan2(v.y, v.x));
    EXPECT_NEAR(std::abs(std::remainder(lon_now - 30.0, 360.0)), 180.0, 1e-6);  // the far side
    EXPECT_LT(latitude_deg(earth, model.offset_m(bodies)), 80.0);               // and down the other side

    // Down to eye height again; walk about with turns and sidesteps.
    for (int i = 0; i < 2000; ++i) model.step({0, -1.0, 0, 0, 0, 0}, 0.05, bodies);
    EXPECT_NEAR(model.altitude_m(bodies), 1.5, 1e-6);
    for (int i = 0; i < 3000; ++i) {
        p = model.step({std::sin(i * 0.01), 0, std::cos(i * 0.013), 0, 0.3, 0}, 0.05, bodies);
        const glm::dvec3 z = glm::normalize(model.offset_m(bodies));
        ASSERT_NEAR(model.altitude_m(bodies), 1.5, 1e-6);
        ASSERT_NEAR(glm::dot(up_of(p.orientation), z), 1.0, 1e-12);
    }
}

TEST(NavSurfaceWalk, WalkSpeedAndPitchLimits) {
    const auto bodies = solar_system();
    const NavBody& earth = body(bodies, 1);
    NavigationModel model;
    model.set_pose({above(earth, kX, 100.0), look(kY, kX)}, bodies);
    model.set_mode(NavMode::SurfaceWalk, bodies);
    const glm::dvec3 before = model.offset_m(bodies);
    for (int i = 0; i < 100; ++i) model.step({0, 0, 1.0, 0, 0, 0}, 0.01, bodies);  // 1 s at 1 m/s
    const glm::dvec3 after = model.offset_m(bodies);
    const double ground = kEarthR * glm::length(glm::normalize(after) - glm::normalize(before));  // chord = arc here
    EXPECT_NEAR(ground, 1.0, 1e-6);
    EXPECT_NEAR(glm::dot(glm::normalize(after - before), kY), 1.0, 1e-6);  // where it looked
    // Look up: clamped at 89 degrees, roll-free (right stays horizontal).
    for (int i = 0; i < 1000; ++i) model.step({0, 0, 0, 1.0, 0, 0}, 0.01, bodies);
    const CameraPose p = model.pose(bodies);
    const glm::dvec3 z = glm::normalize(model.offset_m(bodies));
    EXPECT_NEAR(glm::degrees(std::asin(glm::dot(forward_of(p.orientation), z))), 89.0, 1e-9);
    EXPECT_NEAR(glm::dot(right_of(p.orientation), z), 0.0, 1e-12);
    for (int i = 0; i < 3000; ++i) model.step({0, 0, 0, -1.0, 0, 0}, 0.01, bodies);
    EXPECT_NEAR(glm::degrees(std::asin(glm::dot(forward_of(model.pose(bodies).orientation), z))), -89.0, 1e-9);
    // Roll does nothing on foot.
    const CameraPose q = model.pose(bodies);
    EXPECT_TRUE(bit_identical(model.step({0, 0, 0, 0, 0, 1.0}, 0.5, bodies), q));
}

TEST(NavSurfaceWalk, TurnsWithThePlanet) {
    auto bodies = solar_system(0.0);
    NavigationModel model;
    model.set_pose({above(body(bodies, 1), glm::dvec3(1, 1, 0.5), 10.0), look(kZ, glm::dvec3(-1, -1, 0))}, bodies);
    model.set_mode(NavMode::SurfaceWalk, bodies);
    auto in_body = [&](const CameraPose& p) {
        const NavBody& e = body(bodies, 1);
        return std::make_pair(glm::conjugate(e.orientation) * (p.position_m - e.position_m),
                              glm::conjugate(e.orientation) * p.orientation);
    };
    const auto [pos0, rot0] = in_body(model.pose(bodies));
    for (int i = 1; i <= 100; ++i) {
        bodies = solar_system(0.05 * i);  // the Earth spins under the walker
        const auto [pos, rot] = in_body(model.step(NavAxes{}, 0.01, bodies));
        ASSERT_NEAR(glm::length(pos - pos0), 0.0, 1e-3);  // world rounding at 1 AU
        ASSERT_NEAR(std::abs(glm::dot(rot, rot0)), 1.0, 1e-12);
        // And relative to the anchor (no world rounding): exact to the metre's billionth.
        const NavBody& e = body(bodies, 1);
        ASSERT_NEAR(glm::length(glm::conjugate(e.orientation) * model.offset_m(bodies) - pos0), 0.0, 1e-3);
    }
}

// ---- go-to flights -----------------------------------------------------------------------------

TEST(NavFlyTo, EndsInOrbitLookingAtTheTargetWithLogMonotonicDistance) {
    const auto bodies = solar_system();
    const NavBody& earth = body(bodies, 1);
    NavigationModel model, pressed;
    const CameraPose start{earth.position_m + glm::dvec3(-3.0e9, 4.0e9, 1.0e9), look(kY, kZ)};
    model.set_pose(start, bodies);
    pressed.set_pose(start, bodies);
    model.fly_to(1, 5.0, bodies);
    pressed.fly_to(1, 5.0, bodies);
    EXPECT_TRUE(model.flying());
    EXPECT_EQ(model.mode(), NavMode::Orbit);
    EXPECT_EQ(model.anchor(), 1);
    double prev = glm::length(model.offset_m(bodies));
    double prev_step = 0.0;
    int steps = 0;
    while (model.flying()) {
        const CameraPose p = model.step(NavAxes{}, 1.0 / 60.0, bodies);
        // Input during a flight is ignored.
        const CameraPose q = pressed.step({1, 1, 1, 1, 1, 1}, 1.0 / 60.0, bodies);
        ASSERT_TRUE(bit_identical(p, q));
        ASSERT_TRUE(finite(p));
        const double d = glm::length(model.offset_m(bodies));
        ASSERT_LE(d, prev * (1.0 + 1e-12));
        // Equal time steps take roughly equal log steps in the middle (eased at the ends).
        const double log_step = std::log(prev) - std::log(d);
        if (steps > 100 && steps < 200) {
            ASSERT_LT(std::abs(log_step - prev_step), 0.01);
        }
        prev_step = log_step;
        prev = d;
        ASSERT_LT(++steps, 1000);
    }
    EXPECT_NEAR(steps, 300, 1);
    EXPECT_NEAR(glm::length(model.offset_m(bodies)) / (4.0 * kEarthR) - 1.0, 0.0, 1e-9);
    const CameraPose end = model.pose(bodies);
    EXPECT_GT(glm::dot(forward_of(end.orientation), glm::normalize(earth.position_m - end.position_m)), 1.0 - 1e-12);
    // Now an ordinary orbit: input works again and keeps the distance.
    model.step({0, 0, 0, 0.5, 0.5, 0}, 0.1, bodies);
    EXPECT_NEAR(glm::length(model.offset_m(bodies)) / (4.0 * kEarthR) - 1.0, 0.0, 1e-12);
}

TEST(NavFlyTo, FromSunScaleToTheMoonWithoutNaNOrPassingThroughBodies) {
    auto bodies = solar_system();
    const NavBody& moon = body(bodies, 2);
    NavigationModel model;
    // Far out beyond the Sun, looking away from everything.
    model.set_pose({glm::dvec3(-2.0 * kAU, 0.5 * kAU, 0.3 * kAU), look(glm::dvec3(-1, 0, 0), kZ)}, bodies);
    EXPECT_EQ(model.anchor(), 0);
    model.fly_to(2, 8.0, bodies, 3.0);
    double prev = INFINITY;
    while (model.flying()) {
        const CameraPose p = model.step(NavAxes{}, 1.0 / 30.0, bodies);
        ASSERT_TRUE(finite(p));
        ASSERT_GE(model.altitude_m(bodies), 1.5 - 1e-3);
        const double d = glm::length(model.offset_m(bodies));
        ASSERT_LE(d, prev * (1.0 + 1e-12));
        prev = d;
    }
    EXPECT_NEAR(glm::length(model.offset_m(bodies)) / (3.0 * kMoonR) - 1.0, 0.0, 1e-9);
    const CameraPose end = model.pose(bodies);
    EXPECT_GT(glm::dot(forward_of(end.orientation), glm::normalize(moon.position_m - end.position_m)), 1.0 - 1e-9);

    // The Earth right on the straight way to the Moon: the flight goes around it.
    NavigationModel blocked;
    const glm::dvec3 beyond = body(bodies, 1).position_m - glm::dvec3(5.0e8, 0, 0);  // Moon, Earth, camera in a line
    blocked.set_pose({beyond, look(kX, kZ)}, bodies);
    blocked.fly_to(2, 4.0, bodies);
    prev = INFINITY;
    while (blocked.flying()) {
        ASSERT_TRUE(finite(blocked.step(NavAxes{}, 1.0 / 60.0, bodies)));
        ASSERT_GE(blocked.altitude_m(bodies), 1.5 - 1e-3);
        const double d = glm::length(blocked.offset_m(bodies));
        ASSERT_LE(d, prev * (1.0 + 1e-12));
        prev = d;
    }
    EXPECT_NEAR(glm::length(blocked.offset_m(bodies)) / (4.0 * kMoonR) - 1.0, 0.0, 1e-9);

    // Starting on the Earth's far side: no clear way exists, the flight goes over the surface.
    NavigationModel far_side;
    far_side.set_pose({above(body(bodies, 1), -kX, 100.0), look(kX, kZ)}, bodies);
    far_side.fly_to(2, 3.0, bodies);
    prev = glm::length(far_side.offset_m(bodies));
    const glm::dvec3 earth_from_moon = body(bodies, 1).position_m - body(bodies, 2).position_m;
    while (far_side.flying()) {
        ASSERT_TRUE(finite(far_side.step(NavAxes{}, 1.0 / 60.0, bodies)));
        ASSERT_GE(far_side.altitude_m(bodies), 1.5 - 1e-3);
        // It turns around the Earth before closing in: never lower than where it started over
        // the Earth (a lift over the surface would come down to 1.5 m and break the monotonic
        // distance).
        const glm::dvec3 off = far_side.offset_m(bodies);
        const double d = glm::length(off);
        ASSERT_LE(d, prev * (1.0 + 1e-12));
        ASSERT_GT(glm::length(off - earth_from_moon) - kEarthR, 100.0 - 1e-3);
        prev = d;
    }
    EXPECT_NEAR(glm::length(far_side.offset_m(bodies)) / (4.0 * kMoonR) - 1.0, 0.0, 1e-9);

    // A target that moves during the flight is still reached.
    NavigationModel moving;
    moving.set_pose({glm::dvec3(0.0, kAU, 0.0), look(kX, kZ)}, bodies);
    moving.fly_to(1, 2.0, bodies);
    for (int i = 0; i < 200; ++i) {
        for (auto& b : bodies) b.position_m += glm::dvec3(0, 3.0e4, 0) * (b.id == 0 ? 0.0 : 1.0 / 60.0);
        ASSERT_TRUE(finite(moving.step(NavAxes{}, 1.0 / 60.0, bodies)));
    }
    EXPECT_FALSE(moving.flying());
    EXPECT_NEAR(glm::length(moving.offset_m(bodies)) / (4.0 * kEarthR) - 1.0, 0.0, 1e-9);
}

TEST(NavFlyTo, ZeroDurationJumpsAndUnknownTargetsThrow) {
    const auto bodies = solar_system();
    NavigationModel model;
    model.set_pose({glm::dvec3(1.0e10, 0, 0), look(kY, kZ)}, bodies);
    model.fly_to(1, 0.0, bodies, 10.0);
    EXPECT_FALSE(model.flying());
    EXPECT_NEAR(glm::length(model.offset_m(bodies)) / (10.0 * kEarthR) - 1.0, 0.0, 1e-12);
    EXPECT_THROW(model.fly_to(9, 1.0, bodies), std::invalid_argument);
    EXPECT_THROW(model.set_mode(NavMode::Orbit, bodies, 9), std::invalid_argument);
    // A flight to the body the camera already orbits.
    model.fly_to(1, 1.0, bodies, 2.0);
    while (model.flying()) ASSERT_TRUE(finite(model.step(NavAxes{}, 0.1, bodies)));
    EXPECT_NEAR(glm::length(model.offset_m(bodies)) / (2.0 * kEarthR) - 1.0, 0.0, 1e-9);
    // A mode switch cancels a flight, from where the camera is.
    model.fly_to(0, 10.0, bodies);
    model.step(NavAxes{}, 1.0, bodies);
    const CameraPose mid = model.pose(bodies);
    model.set_mode(NavMode::FreeFly, bodies);
    EXPECT_FALSE(model.flying());
    EXPECT_NEAR(glm::length(model.pose(bodies).position_m - mid.position_m), 0.0, 1e-3);
}

// ---- precision and degenerate input ------------------------------------------------------------

TEST(NavPrecision, MillimetreStepsAt1p5e11Metres) {
    const auto bodies = solar_system();
    NavigationTuning t;
    t.speed_per_altitude = 0.0;
    t.min_speed_m_s = 1.0e-3;  // 1 mm/s whatever the altitude
    NavigationModel model(t);
    model.set_pose({above(body(bodies, 1), glm::dvec3(0.2, 0.9, 0.1), 1.0e5), look(glm::dvec3(1, 0.3, 0.2), kZ)},
                   bodies);
    ASSERT_EQ(model.anchor(), 1);
    ASSERT_GT(glm::length(model.pose(bodies).position_m), 1.49e11);
    for (int step = 0; step < 5; ++step) {
        const glm::dvec3 before = model.offset_m(bodies);
        model.step({0, 0, 1.0, 0, 0, 0}, 1.0, bodies);
        EXPECT_NEAR(glm::length(model.offset_m(bodies) - before), 1.0e-3, 1.0e-6);
    }
    // A thousand 1 ms frames add up to the same millimetre.
    const glm::dvec3 before = model.offset_m(bodies);
    for (int i = 0; i < 1000; ++i) model.step({0, 0, 1.0, 0, 0, 0}, 1.0e-3, bodies);
    EXPECT_NEAR(glm::length(model.offset_m(bodies) - before), 1.0e-3, 1.0e-6);
}

TEST(NavDegenerate, PolesStraightDownZeroAndHugeDtNoNaN) {
    const auto bodies = solar_system();
    const NavBody& earth = body(bodies, 1);
    const glm::dvec3 pole = earth.orientation * kZ;
    // Exactly above the north pole, looking straight down.
    NavigationModel model;
    model.set_pose({earth.position_m + pole * (kEarthR + 1.0e6), look(-pole, earth.orientation * kX)}, bodies);
    const glm::dvec3 top_of_picture = up_of(model.pose(bodies).orientation);
    model.set_mode(NavMode::SurfaceWalk, bodies);
    CameraPose p = model.pose(bodies);
    ASSERT_TRUE(finite(p));
    EXPECT_NEAR(glm::dot(up_of(p.orientation), pole), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(forward_of(p.orientation), top_of_picture), 1.0, 1e-9);  // heading: picture's top
    EXPECT_NEAR(model.altitude_m(bodies), 1.5, 1e-6);
    // Looking straight up.
    NavigationModel up;
    up.set_pose({earth.position_m - pole * (kEarthR + 1.0e3), look(-pole, kX)}, bodies);
    up.set_mode(NavMode::SurfaceWalk, bodies);
    EXPECT_TRUE(finite(up.pose(bodies)));
    EXPECT_NEAR(glm::dot(up_of(up.pose(bodies).orientation), -pole), 1.0, 1e-12);

    const std::vector<NavAxes> inputs{
        {}, {1, 1, 1, 1, 1, 1}, {-1, -1, -1, -1, -1, -1}, {NAN, INFINITY, -INFINITY, NAN, 2.0, -7.0}};
    const std::vector<double> dts{0.0, -1.0, 1e-12, 1.0 / 60.0, 1e6, 1e9, NAN, INFINITY};
    for (NavMode m : {NavMode::SurfaceWalk, NavMode::Orbit, NavMode::FreeFly}) {
        NavigationModel n;
        n.set_pose({earth.position_m + pole * (kEarthR + 1.0e6), look(-pole, kX)}, bodies);
        n.set_mode(m, bodies, 1);  // target == anchor
        for (const NavAxes& in : inputs)
            for (double dt : dts) {
                p = n.step(in, dt, bodies);
                ASSERT_TRUE(finite(p)) << nav_mode_name(m) << " dt " << dt;
                ASSERT_GE(n.altitude_m(bodies), 1.5 - 1e-3) << nav_mode_name(m) << " dt " << dt;
            }
        // Zero dt and no input: nothing moves.
        const CameraPose before = n.pose(bodies);
        EXPECT_TRUE(bit_identical(n.step({1, 1, 1, 1, 1, 1}, 0.0, bodies), before)) << nav_mode_name(m);
    }
    // Orbit entered exactly at the target's centre, and with no bodies at all.
    NavigationModel centre;
    centre.set_pose({earth.position_m, glm::dquat(0, 0, 0, 0)}, bodies);
    centre.set_mode(NavMode::Orbit, bodies);
    EXPECT_TRUE(finite(centre.step({0, 0, 1, 1, 1, 1}, 0.1, bodies)));
    NavigationModel empty;
    empty.set_pose({glm::dvec3(1, 2, 3), look(kX, kZ)}, {});
    EXPECT_TRUE(finite(empty.step({0, 0, 1, 0, 0, 0}, 1.0, {})));
    EXPECT_TRUE(std::isinf(empty.altitude_m({})));
}

TEST(NavModes, NamesAndSceneBodies) {
    for (NavMode m : {NavMode::Orbit, NavMode::FreeFly, NavMode::SurfaceWalk})
        EXPECT_EQ(nav_mode_from_name(nav_mode_name(m)), m);
    EXPECT_FALSE(nav_mode_from_name("warp").has_value());

    SceneConfig scene;
    scene.bodies.resize(2);
    scene.bodies[0].id = 0, scene.bodies[0].name = "sun", scene.bodies[0].radius_m = kSunR;
    scene.bodies[1].id = 1, scene.bodies[1].name = "earth", scene.bodies[1].radius_m = kEarthR;
    std::vector<BodyState> states(3);
    states[0].id = 1, states[0].position_m = glm::dvec3(kAU, 0, 0);
    states[1].id = 0;
    states[2].id = 7;  // not in the scene: left out
    const auto nb = nav_bodies(scene, states);
    ASSERT_EQ(nb.size(), 2u);
    EXPECT_EQ(nb[0].id, 1);
    EXPECT_EQ(nb[0].name, "earth");
    EXPECT_EQ(nb[0].radius_m, kEarthR);
    EXPECT_EQ(nb[0].position_m, glm::dvec3(kAU, 0, 0));
    EXPECT_EQ(nb[1].name, "sun");
}

#pragma once
// Flying the dome with a 3D mouse or gamepad: turns shaped device axes (navigation/input_shaper)
// into a camera pose, in one of three modes, plus eased "go to" flights between bodies.
//
//   Orbit        around a target body, always looking at its centre at a stored distance:
//                yaw_left + right and pitch_up - up swing the camera around the centre,
//                roll_ccw rolls about the view axis, forward zooms (the altitude above the surface
//                changes by exp(-speed_per_altitude * forward * dt), never below min_altitude_m).
//   FreeFly      translate along the camera's axes at max(min_speed_m_s, speed_per_altitude x
//                altitude above the nearest surface) x deflection, turn at turn_rate_deg_s;
//                never closer to a surface than min_altitude_m.
//   SurfaceWalk  on a body, in body-fixed coordinates (the camera turns with the planet):
//                forward/right walk along the surface, up raises the eye (>= min_altitude_m),
//                yaw_left turns the heading about the zenith, pitch_up tilts the view (+-89 deg);
//                the horizon stays level and the camera's up is the local zenith at zero pitch.
//
// Precision: the camera is held relative to an anchor body (its centre, world axes), never as an
// accumulated world position, so steps of a millimetre survive 1.5e11 m from the world origin.
// Orbit and FreeFly keep the offset from the anchor fixed in world axes while the anchor moves;
// FreeFly re-anchors to whichever body is nearest (by distance to its surface), re-expressing
// the offset so that the world position is continuous.
//
// Every body is a sphere of NavBody::radius_m. The bodies passed to each call are at the
// simulation time the pose is for; a body missing from the list is taken where it was last seen.
#include <optional>
#include <string>
#include <vector>

#include "input/nav_input.hpp"
#include "navigation/nav_body.hpp"

namespace cupola {

enum class NavMode { Orbit, FreeFly, SurfaceWalk };

const char* nav_mode_name(NavMode m);  // "orbit", "free_fly", "surface_walk"
std::optional<NavMode> nav_mode_from_name(const std::string& name);

struct NavigationTuning {
    double speed_per_altitude =
        0.5;  // full deflection moves this fraction of the altitude above the nearest surface per second
    double min_speed_m_s = 1.0;      // floor (walking pace on a surface)
    double turn_rate_deg_s = 45.0;   // full deflection rotation rate (free fly look / surface look / orbit roll)
    double orbit_rate_deg_s = 30.0;  // full deflection orbit angular rate
    double min_altitude_m = 1.5;     // never below a surface by less than this (eye height on foot)
};

// The course of a go-to flight, relative to the target's centre (world axes): the direction from
// the target slerps dir0 -> dir1 and the log of the distance goes log_d0 -> log_d1, each eased,
// over its own part of the flight (u = 0..1): the direction over [0, dir_end], the distance over
// [dist_start, 1]. Turning before closing in lets a flight round a body next to its start.
struct NavFlightPath {
    glm::dvec3 dir0{0.0, 0.0, 1.0}, dir1{0.0, 0.0, 1.0};  // unit, target -> camera
    double log_d0 = 0.0, log_d1 = 0.0;                    // ln of the distance to the centre
    double dir_end = 1.0, dist_start = 0.0;
    glm::dvec3 offset_at(double u) const;  // camera - target centre at flight fraction u
};

class NavigationModel {
public:
    explicit NavigationModel(NavigationTuning t = {});

    // Takes over from a pose (e.g. the show's camera when the presenter grabs the device): free
    // fly, anchored to the body whose surface is nearest the pose. A pose closer than
    // min_altitude_m to a surface (or inside a body) is lifted radially to min_altitude_m.
    // Cancels a flight.
    void set_pose(const CameraPose& pose, const std::vector<NavBody>& bodies);

    // Switch mode keeping the camera where it is as far as the mode allows (cancels a flight):
    //   Orbit: around `target` (default: the current anchor), which becomes the anchor, at the
    //          current distance from its centre, turned by the smallest rotation that looks at it;
    //   SurfaceWalk: on `target` (default: the anchor), at min_altitude_m above the surface point
    //          below the camera, horizon level, heading kept (looking straight down or up: the
    //          heading is where the top of the picture pointed);
    //   FreeFly: the pose is kept, anchored to the nearest body (`target` is not used).
    // Throws std::invalid_argument when `target` names no body in `bodies`.
    void set_mode(NavMode m, const std::vector<NavBody>& bodies, std::optional<uint16_t> target = std::nullopt);

    // An eased flight of duration_s seconds (of step() time) ending in Orbit around `target` at
    // distance_radii x its radius from its centre (at least min_altitude_m above the surface, or
    // min_distance_m from the centre when that is given: a relief lower than the sphere), looking
    // at it. Seen from the target, the distance is interpolated in log space and the
    // direction by slerp, so the distance falls (or rises) monotonically and the path never
    // enters the target. When another body blocks the straight way in, the end direction is
    // turned away from it (by the smallest of a few angles that clears it, turning before closing
    // in where needed: NavFlightPath); any point still inside another body is lifted radially
    // to min_altitude_m (the fallback when no clear course was found).
    // The orientation slerps to the final look-at. Input is ignored while flying(); mode() is
    // already Orbit and anchor() the target. duration_s <= 0 jumps there at once.
    // Throws std::invalid_argument when `target` names no body in `bodies`.
    void fly_to(uint16_t target, double duration_s, const std::vector<NavBody>& bodies, double distance_radii = 4.0,
                double min_distance_m = 0.0);
    // Where the camera is, or lands when it is flying, seen from the anchor's centre (unit, world
    // axes): in Orbit, orientation * +Z.
    glm::dvec3 landing_direction() const;

    // Advance by dt_s seconds of wall time with shaped input; `bodies` are at the NEW simulation
    // time. dt_s <= 0 or non-finite moves nothing (but the camera still rides with its anchor);
    // axes are clamped to -1..1 and a non-finite axis reads as 0. Returns the new pose.
    CameraPose step(const NavAxes& in, double dt_s, const std::vector<NavBody>& bodies);

    CameraPose pose(const std::vector<NavBody>& bodies) const;
    // The camera position relative to the anchor's centre, world axes (what pose() adds to the
    // anchor's position; exact where the world position would round at astronomical distances).
    glm::dvec3 offset_m(const std::vector<NavBody>& bodies) const;

    NavMode mode() const { return mode_; }
    uint16_t anchor() const { return anchor_; }
    bool flying() const { return flight_.has_value(); }
    const NavigationTuning& tuning() const { return tuning_; }

    // Altitude above the nearest body's surface (+infinity with no bodies).
    double altitude_m(const std::vector<NavBody>& bodies) const;

private:
    // A go-to flight to the anchor (its target).
    struct Flight {
        double duration_s = 0.0, elapsed_s = 0.0;
        NavFlightPath path;
        double d1 = 1.0;                                            // final distance to the centre
        glm::dquat q0{1.0, 0.0, 0.0, 0.0}, q1{1.0, 0.0, 0.0, 0.0};  // camera -> world, eased over the whole flight
    };
    struct Relative {       // a pose relative to the anchor's centre
        glm::dvec3 offset;  // world axes
        glm::dquat orientation;
    };

    const NavBody& anchor_body(const std::vector<NavBody>& bodies) const;
    Relative relative_pose(const std::vector<NavBody>& bodies) const;
    Relative flight_pose(const std::vector<NavBody>& bodies) const;
    double speed_at(double altitude_m) const;

    void enter_free_fly(const Relative& r, const std::vector<NavBody>& bodies);
    void enter_orbit(const Relative& r, const NavBody& target, const std::vector<NavBody>& bodies);
    void enter_surface_walk(const Relative& r, const NavBody& target, const std::vector<NavBody>& bodies);
    void reanchor_to_nearest(const std::vector<NavBody>& bodies);

    void step_orbit(const NavAxes& in, double dt);
    void step_free_fly(const NavAxes& in, double dt, const std::vector<NavBody>& bodies);
    void step_surface_walk(const NavAxes& in, double dt);

    NavigationTuning tuning_;
    NavMode mode_ = NavMode::FreeFly;
    uint16_t anchor_ = 0;
    NavBody anchor_seen_;  // the anchor as last seen (used while it is missing from the list)

    // FreeFly and Orbit: camera -> world.
    glm::dquat orientation_{1.0, 0.0, 0.0, 0.0};
    // FreeFly: camera position - anchor centre, world axes.
    glm::dvec3 offset_{0.0, 0.0, 0.0};
    // Orbit: distance from the anchor's centre; the camera sits at orientation_ * (0, 0, distance).
    double distance_m_ = 1.0;
    // SurfaceWalk: the walker's frame (x right, y heading, z zenith) -> body frame, the eye height
    // above the surface and the view's elevation above the horizon.
    glm::dquat walker_{1.0, 0.0, 0.0, 0.0};
    double eye_height_m_ = 1.5;
    double look_pitch_rad_ = 0.0;

    std::optional<Flight> flight_;
};

}  // namespace cupola

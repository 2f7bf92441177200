#include "navigation/navigation_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cupola {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxDistance_m = 1.0e18;             // about 100 light years: nothing flies farther
constexpr double kMaxPitch_rad = 89.0 * kPi / 180.0;  // surface walk: look up/down at most this
constexpr int kFlightSamples = 256;                   // samples when checking a flight path is clear

const glm::dvec3 kX(1.0, 0.0, 0.0), kY(0.0, 1.0, 0.0), kZ(0.0, 0.0, 1.0);

double deg(double d) { return d * kPi / 180.0; }

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// One axis as the model uses it: -1..1, 0 when not a number.
double clean_axis(double x) { return std::isfinite(x) ? std::clamp(x, -1.0, 1.0) : 0.0; }

NavAxes clean(const NavAxes& a) {
    return {clean_axis(a.right),    clean_axis(a.up),       clean_axis(a.forward),
            clean_axis(a.pitch_up), clean_axis(a.yaw_left), clean_axis(a.roll_ccw)};
}

// A usable rotation from whatever a caller passed: normalised, identity when zero or not finite.
glm::dquat clean_orientation(const glm::dquat& q) {
    const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!std::isfinite(n) || n < 1e-12) return {1.0, 0.0, 0.0, 0.0};
    return q / n;
}

// The rotation by |w| radians about w (identity for w = 0).
glm::dquat rotation_from_vector(const glm::dvec3& w) {
    const double angle = glm::length(w);
    if (angle == 0.0 || !std::isfinite(angle)) return {1.0, 0.0, 0.0, 0.0};
    return glm::angleAxis(angle, w / angle);
}

// Some unit vector perpendicular to the unit vector v.
glm::dvec3 any_perpendicular(const glm::dvec3& v) {
    const glm::dvec3 other = std::abs(v.x) < 0.9 ? kX : kY;
    return glm::normalize(glm::cross(v, other));
}

// The smallest rotation taking unit vector `from` to unit vector `to`; half a turn about
// `fallback_axis` (made perpendicular to `from`) when they are opposite.
glm::dquat rotation_between(const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& fallback_axis) {
    const glm::dvec3 axis = glm::cross(from, to);
    const double s = glm::length(axis), c = glm::dot(from, to);
    if (s > 1e-12) return glm::angleAxis(std::atan2(s, c), axis / s);
    if (c > 0.0) return {1.0, 0.0, 0.0, 0.0};
    glm::dvec3 a = fallback_axis - from * glm::dot(fallback_axis, from);
    a = glm::length(a) > 1e-9 ? glm::normalize(a) : any_perpendicular(from);
    return glm::angleAxis(kPi, a);
}

// Spherical interpolation of unit vectors (not through opposite vectors: callers avoid them).
glm::dvec3 slerp_direction(const glm::dvec3& a, const glm::dvec3& b, double s) {
    const double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
    if (angle < 1e-9) return glm::normalize(a + (b - a) * s);
    const double sa = std::sin(angle);
    return glm::normalize(a * (std::sin((1.0 - s) * angle) / sa) + b * (std::sin(s * angle) / sa));
}

// Ease in and out: 0 -> 0, 1 -> 1, monotonic, zero slope at both ends.
double ease(double u) {
    u = std::clamp(u, 0.0, 1.0);
    return u * u * (3.0 - 2.0 * u);
}

// A body as an obstacle: centre relative to some origin (world axes) and radius.
struct Sphere {
    uint16_t id;
    glm::dvec3 centre;
    double radius;
};

// The bodies as spheres relative to `origin`, each radius grown by `inflate`.
std::vector<Sphere> spheres(const std::vector<NavBody>& bodies, const glm::dvec3& origin, double inflate) {
    std::vector<Sphere> out;
    out.reserve(bodies.size());
    for (const NavBody& b : bodies) out.push_back({b.id, b.position_m - origin, b.radius_m + inflate});
    return out;
}

// Distance from p to the nearest sphere's surface (+infinity with none).
double clearance(const glm::dvec3& p, const std::vector<Sphere>& s) {
    double best = std::numeric_limits<double>::infinity();
    for (const Sphere& b : s) best = std::min(best, glm::length(p - b.centre) - b.radius);
    return best;
}

// p moved radially onto the surface of every sphere it is inside (`away`: the direction used
// when p is exactly at a centre).
glm::dvec3 push_out(glm::dvec3 p, const std::vector<Sphere>& s, const glm::dvec3& away) {
    for (const Sphere& b : s) {
        const glm::dvec3 v = p - b.centre;
        const double d = glm::length(v);
        if (d < b.radius) p = b.centre + (d > 0.0 ? v / d : away) * b.radius;
    }
    return p;
}

// The end of a move from `start` by `delta` that does not pass through a sphere: a move that
// would enter one stops at its surface and keeps only the part of the rest along the surface
// (so pressing into a planet slides over it), then anything left inside is pushed out.
glm::dvec3 move_clear(const glm::dvec3& start, const glm::dvec3& delta, const std::vector<Sphere>& s,
                      const glm::dvec3& away) {
    const double a = glm::dot(delta, delta);
    double t_hit = 2.0;
    const Sphere* hit = nullptr;
    for (const Sphere& b : s) {
        const glm::dvec3 o = start - b.centre;
        const double c = glm::dot(o, o) - b.radius * b.radius;  // > 0: start outside
        const double h = glm::dot(o, delta);                    // < 0: moving toward the centre
        if (a == 0.0 || c <= 0.0 || h >= 0.0) continue;
        const double disc = h * h - a * c;
        if (disc < 0.0) continue;
        const double t = (-h - std::sqrt(disc)) / a;  // first crossing of the surface
        if (t >= 0.0 && t <= 1.0 && t < t_hit) t_hit = t, hit = &b;
    }
    glm::dvec3 end = start + delta;
    if (hit) {
        const glm::dvec3 entry = start + delta * t_hit;
        glm::dvec3 rest = delta * (1.0 - t_hit);
        const glm::dvec3 n = glm::normalize(entry - hit->centre);
        const double inward = glm::dot(rest, n);
        if (inward < 0.0) rest -= n * inward;
        end = entry + rest;
    }
    end = push_out(end, s, away);
    const double len = glm::length(end);
    if (len > kMaxDistance_m) end *= kMaxDistance_m / len;
    return end;
}

// Whether a course keeps out of every sphere (relative to the target), sampled; `blocker` gets
// the first sphere in the way.
bool flight_clear(const NavFlightPath& path, const std::vector<Sphere>& obstacles, const Sphere** blocker) {
    for (int i = 0; i <= kFlightSamples; ++i) {
        const glm::dvec3 p = path.offset_at(double(i) / kFlightSamples);
        for (const Sphere& b : obstacles)
            if (glm::length(p - b.centre) < b.radius * (1.0 - 1e-9)) {
                if (blocker) *blocker = &b;
                return false;
            }
    }
    return true;
}

// The course of a flight from dir0 (from the target) at distance exp(log_d0) to exp(log_d1):
// straight in along dir0 when that is clear; otherwise ending in dir0 turned away from the
// first body in the way, by the smallest angle that clears it out of a few multiples of the
// body's apparent radius seen from the target and 30..150 degrees, first turning while closing
// in, then turning before closing in. Nothing clear: straight in (the push-out lifts the camera
// over the body while flying).
NavFlightPath plan_flight(const glm::dvec3& dir0, double log_d0, double log_d1, const std::vector<Sphere>& obstacles) {
    NavFlightPath path;
    path.dir0 = path.dir1 = dir0;
    path.log_d0 = log_d0;
    path.log_d1 = log_d1;
    const Sphere* blocker = nullptr;
    if (flight_clear(path, obstacles, &blocker) || !blocker) return path;

    const double bl = glm::length(blocker->centre);
    const glm::dvec3 b = bl > 0.0 ? blocker->centre / bl : any_perpendicular(dir0);
    glm::dvec3 axis = glm::cross(b, dir0);  // turning dir0 about it moves it away from b
    axis = glm::length(axis) > 1e-9 ? glm::normalize(axis) : any_perpendicular(dir0);
    const double apparent = bl > blocker->radius ? std::asin(blocker->radius / bl) : kPi / 2.0;
    std::vector<double> angles{1.5 * apparent, 3.0 * apparent, 6.0 * apparent};
    for (int k = 1; k <= 5; ++k) angles.push_back(deg(30.0 * k));
    std::sort(angles.begin(), angles.end());
    for (double a : angles) {
        if (a <= 0.0 || a > deg(150.0)) continue;
        NavFlightPath turned = path;
        turned.dir1 = glm::normalize(glm::angleAxis(a, axis) * dir0);
        if (flight_clear(turned, obstacles, nullptr)) return turned;
        turned.dir_end = 0.6;     // turn first ...
        turned.dist_start = 0.4;  // ... then close in
        if (flight_clear(turned, obstacles, nullptr)) return turned;
    }
    return path;
}

}  // namespace

glm::dvec3 NavFlightPath::offset_at(double u) const {
    const double sd = ease(dir_end > 0.0 ? u / dir_end : 1.0);
    const double sl = ease(dist_start < 1.0 ? (u - dist_start) / (1.0 - dist_start) : 1.0);
    return slerp_direction(dir0, dir1, sd) * std::exp(log_d0 + (log_d1 - log_d0) * sl);
}

const char* nav_mode_name(NavMode m) {
    switch (m) {
        case NavMode::Orbit:
            return "orbit";
        case NavMode::FreeFly:
            return "free_fly";
        case NavMode::SurfaceWalk:
            return "surface_walk";
    }
    return "?";
}

std::optional<NavMode> nav_mode_from_name(const std::string& name) {
    for (NavMode m : {NavMode::Orbit, NavMode::FreeFly, NavMode::SurfaceWalk})
        if (name == nav_mode_name(m)) return m;
    return std::nullopt;
}

NavigationModel::NavigationModel(NavigationTuning t) : tuning_(t) {
    // Keep the arithmetic defined whatever a configuration says.
    auto sane = [](double& v, double fallback) {
        if (!std::isfinite(v) || v < 0.0) v = fallback;
    };
    sane(tuning_.speed_per_altitude, 0.5);
    sane(tuning_.min_speed_m_s, 1.0);
    sane(tuning_.turn_rate_deg_s, 45.0);
    sane(tuning_.orbit_rate_deg_s, 30.0);
    sane(tuning_.min_altitude_m, 1.5);
    eye_height_m_ = tuning_.min_altitude_m;
}

const NavBody& NavigationModel::anchor_body(const std::vector<NavBody>& bodies) const {
    for (const NavBody& b : bodies)
        if (b.id == anchor_) return b;
    return anchor_seen_;
}

double NavigationModel::speed_at(double altitude_m) const {
    if (!std::isfinite(altitude_m)) return tuning_.min_speed_m_s;
    return std::max(tuning_.min_speed_m_s, tuning_.speed_per_altitude * std::max(altitude_m, 0.0));
}

// ---- poses -------------------------------------------------------------------------------------

NavigationModel::Relative NavigationModel::flight_pose(const std::vector<NavBody>& bodies) const {
    const Flight& f = *flight_;
    const double u = std::clamp(f.elapsed_s / f.duration_s, 0.0, 1.0);
    glm::dvec3 offset = f.path.offset_at(u);
    // Other bodies may have moved into the way: lift the camera over them.
    const NavBody& target = anchor_body(bodies);
    std::vector<Sphere> others;
    for (const Sphere& b : spheres(bodies, target.position_m, tuning_.min_altitude_m))
        if (b.id != anchor_) others.push_back(b);
    offset = push_out(offset, others, f.path.dir0);
    return {offset, glm::normalize(glm::slerp(f.q0, f.q1, ease(u)))};
}

NavigationModel::Relative NavigationModel::relative_pose(const std::vector<NavBody>& bodies) const {
    if (flight_) return flight_pose(bodies);
    switch (mode_) {
        case NavMode::Orbit:
            return {orientation_ * glm::dvec3(0.0, 0.0, distance_m_), orientation_};
        case NavMode::FreeFly:
            return {offset_, orientation_};
        case NavMode::SurfaceWalk: {
            const NavBody& b = anchor_body(bodies);
            const glm::dquat walker_world = clean_orientation(b.orientation) * walker_;
            const glm::dvec3 zenith = walker_world * kZ;
            // Camera frame -> walker frame: +X right, +Y zenith, +Z behind (a quarter turn about
            // x), then the view tilted up by the pitch.
            const glm::dquat cam = glm::normalize(walker_world * glm::angleAxis(kPi / 2.0 + look_pitch_rad_, kX));
            return {zenith * (b.radius_m + eye_height_m_), cam};
        }
    }
    return {offset_, orientation_};
}

CameraPose NavigationModel::pose(const std::vector<NavBody>& bodies) const {
    const Relative r = relative_pose(bodies);
    return {anchor_body(bodies).position_m + r.offset, r.orientation};
}

glm::dvec3 NavigationModel::offset_m(const std::vector<NavBody>& bodies) const { return relative_pose(bodies).offset; }

double NavigationModel::altitude_m(const std::vector<NavBody>& bodies) const {
    const NavBody& a = anchor_body(bodies);
    return clearance(relative_pose(bodies).offset, spheres(bodies, a.position_m, 0.0));
}

// ---- taking over and switching modes ---------------------------------------------------------

void NavigationModel::reanchor_to_nearest(const std::vector<NavBody>& bodies) {
    const NavBody& a = anchor_body(bodies);
    const glm::dvec3 origin = a.position_m;
    const NavBody* best = nullptr;
    double best_alt = glm::length(offset_) - a.radius_m;  // only a strictly nearer body takes over
    for (const NavBody& b : bodies) {
        const double alt = glm::length(offset_ - (b.position_m - origin)) - b.radius_m;
        if (alt < best_alt) best_alt = alt, best = &b;
    }
    if (!best || best->id == anchor_) return;
    offset_ -= best->position_m - origin;  // same world position, now from the new anchor
    anchor_ = best->id;
    anchor_seen_ = *best;
}

void NavigationModel::enter_free_fly(const Relative& r, const std::vector<NavBody>& bodies) {
    mode_ = NavMode::FreeFly;
    orientation_ = clean_orientation(r.orientation);
    offset_ = finite(r.offset) ? r.offset : glm::dvec3(0.0);
    const NavBody& a = anchor_body(bodies);
    offset_ = push_out(offset_, spheres(bodies, a.position_m, tuning_.min_altitude_m), orientation_ * kZ);
    reanchor_to_nearest(bodies);
}

void NavigationModel::enter_orbit(const Relative& r, const NavBody& target, const std::vector<NavBody>& bodies) {
    const glm::dvec3 from_target = r.offset - (target.position_m - anchor_body(bodies).position_m);
    const glm::dquat q = clean_orientation(r.orientation);
    const double d = glm::length(from_target);
    const glm::dvec3 dir = (d > 0.0 && std::isfinite(d)) ? from_target / d : q * kZ;
    // The smallest turn that puts the target's centre straight ahead keeps the roll familiar.
    orientation_ = glm::normalize(rotation_between(q * -kZ, -dir, q * kY) * q);
    const double d_min = target.radius_m + tuning_.min_altitude_m;
    distance_m_ = std::clamp(std::isfinite(d) ? d : d_min, d_min, kMaxDistance_m);
    anchor_ = target.id;
    anchor_seen_ = target;
    mode_ = NavMode::Orbit;
}

void NavigationModel::enter_surface_walk(const Relative& r, const NavBody& target, const std::vector<NavBody>& bodies) {
    const glm::dvec3 from_target = r.offset - (target.position_m - anchor_body(bodies).position_m);
    const glm::dquat to_body = glm::conjugate(clean_orientation(target.orientation));
    const glm::dquat q = clean_orientation(r.orientation);
    const double d = glm::length(from_target);
    const glm::dvec3 zenith = (d > 0.0 && std::isfinite(d)) ? to_body * (from_target / d) : kZ;  // body frame
    auto horizontal = [&](const glm::dvec3& v) { return v - zenith * glm::dot(v, zenith); };
    // Heading: the view direction laid on the horizon; looking straight down it is where the top
    // of the picture points, straight up where its bottom points; failing all, north.
    const glm::dvec3 fwd = to_body * (q * -kZ), up = to_body * (q * kY);
    glm::dvec3 heading = horizontal(fwd);
    if (glm::length(heading) < 1e-6) heading = glm::dot(fwd, zenith) < 0.0 ? horizontal(up) : -horizontal(up);
    if (glm::length(heading) < 1e-6) heading = horizontal(kZ);
    if (glm::length(heading) < 1e-6) heading = horizontal(kX);
    heading = glm::normalize(heading);
    const glm::dvec3 right = glm::cross(heading, zenith);
    walker_ = glm::normalize(glm::quat_cast(glm::dmat3(right, heading, zenith)));
    eye_height_m_ = tuning_.min_altitude_m;
    look_pitch_rad_ = 0.0;
    anchor_ = target.id;
    anchor_seen_ = target;
    mode_ = NavMode::SurfaceWalk;
}

void NavigationModel::set_pose(const CameraPose& pose, const std::vector<NavBody>& bodies) {
    flight_.reset();
    const glm::dvec3 p = finite(pose.position_m) ? pose.position_m : glm::dvec3(0.0);
    // The body whose surface is nearest.
    const NavBody* best = nullptr;
    double best_alt = std::numeric_limits<double>::infinity();
    for (const NavBody& b : bodies) {
        const double alt = glm::length(p - b.position_m) - b.radius_m;
        if (!best || alt < best_alt) best_alt = alt, best = &b;
    }
    if (best) {
        anchor_ = best->id;
        anchor_seen_ = *best;
    } else {  // no bodies: the world origin stands in for an anchor
        anchor_ = 0;
        anchor_seen_ = NavBody{0, "", 0.0, glm::dvec3(0.0), glm::dquat(1.0, 0.0, 0.0, 0.0)};
    }
    enter_free_fly({p - anchor_seen_.position_m, pose.orientation}, bodies);
}

void NavigationModel::set_mode(NavMode m, const std::vector<NavBody>& bodies, std::optional<uint16_t> target) {
    std::optional<NavBody> chosen;
    if (target) {
        for (const NavBody& b : bodies)
            if (b.id == *target) chosen = b;
        if (!chosen) throw std::invalid_argument("navigation: no body with id " + std::to_string(*target));
    }
    const Relative r = relative_pose(bodies);
    flight_.reset();
    anchor_seen_ = anchor_body(bodies);
    const NavBody t = chosen ? *chosen : anchor_seen_;
    switch (m) {
        case NavMode::Orbit:
            enter_orbit(r, t, bodies);
            break;
        case NavMode::FreeFly:
            enter_free_fly(r, bodies);
            break;
        case NavMode::SurfaceWalk:
            enter_surface_walk(r, t, bodies);
            break;
    }
}

glm::dvec3 NavigationModel::landing_direction() const { return glm::normalize(orientation_ * kZ); }

void NavigationModel::fly_to(uint16_t target, double duration_s, const std::vector<NavBody>& bodies,
                             double distance_radii, double min_distance_m) {
    const NavBody* found = nullptr;
    for (const NavBody& b : bodies)
        if (b.id == target) found = &b;
    if (!found) throw std::invalid_argument("navigation: no body with id " + std::to_string(target));
    const NavBody t = *found;

    const Relative r = relative_pose(bodies);
    const glm::dvec3 from_target = r.offset - (t.position_m - anchor_body(bodies).position_m);
    const glm::dquat q0 = clean_orientation(r.orientation);
    const double d_min = min_distance_m > 0.0 ? min_distance_m : t.radius_m + tuning_.min_altitude_m;
    double d0 = glm::length(from_target);
    const glm::dvec3 dir0 = (d0 > 0.0 && std::isfinite(d0)) ? from_target / d0 : q0 * kZ;
    d0 = std::clamp(std::isfinite(d0) ? d0 : d_min, d_min, kMaxDistance_m);
    const double radii = (std::isfinite(distance_radii) && distance_radii > 0.0) ? distance_radii : 4.0;
    const double d1 = std::clamp(radii * t.radius_m, d_min, kMaxDistance_m);

    std::vector<Sphere> others;
    for (const Sphere& b : spheres(bodies, t.position_m, tuning_.min_altitude_m))
        if (b.id != t.id) others.push_back(b);
    Flight f;
    f.duration_s = duration_s;
    f.path = plan_flight(dir0, std::log(d0), std::log(d1), others);
    f.d1 = d1;
    f.q0 = q0;
    f.q1 = glm::normalize(rotation_between(q0 * -kZ, -f.path.dir1, q0 * kY) * q0);

    anchor_ = t.id;
    anchor_seen_ = t;
    mode_ = NavMode::Orbit;
    orientation_ = f.q1;  // where the flight ends
    distance_m_ = d1;
    if (std::isfinite(duration_s) && duration_s > 0.0)
        flight_ = f;
    else
        flight_.reset();
}

// ---- stepping ----------------------------------------------------------------------------------

void NavigationModel::step_orbit(const NavAxes& in, double dt) {
    // Swing around the centre: rotating the camera about its own axes moves it on the sphere of
    // radius distance_m_ (it sits at orientation_ * (0, 0, distance_m_)); translation right/up
    // swings it right/up.
    const double orbit = deg(tuning_.orbit_rate_deg_s) * dt, turn = deg(tuning_.turn_rate_deg_s) * dt;
    const glm::dvec3 w((in.pitch_up - in.up) * orbit, (in.yaw_left + in.right) * orbit, in.roll_ccw * turn);
    if (w != glm::dvec3(0.0)) orientation_ = glm::normalize(orientation_ * rotation_from_vector(w));
    if (in.forward != 0.0 && dt > 0.0) {
        const double radius = anchor_seen_.radius_m;
        const double h = std::max(distance_m_ - radius, 1e-6) * std::exp(-tuning_.speed_per_altitude * in.forward * dt);
        distance_m_ =
            radius + std::clamp(std::isfinite(h) ? h : kMaxDistance_m, tuning_.min_altitude_m, kMaxDistance_m);
    }
}

void NavigationModel::step_free_fly(const NavAxes& in, double dt, const std::vector<NavBody>& bodies) {
    const double turn = deg(tuning_.turn_rate_deg_s) * dt;
    const glm::dvec3 w(in.pitch_up * turn, in.yaw_left * turn, in.roll_ccw * turn);
    if (w != glm::dvec3(0.0)) orientation_ = glm::normalize(orientation_ * rotation_from_vector(w));

    const glm::dvec3 origin = anchor_seen_.position_m;
    const auto solid = spheres(bodies, origin, 0.0);
    const auto keep_out = spheres(bodies, origin, tuning_.min_altitude_m);
    const glm::dvec3 wish(in.right, in.up, -in.forward);  // camera frame
    if (wish != glm::dvec3(0.0) && dt > 0.0) {
        const double speed = speed_at(clearance(offset_, solid));
        offset_ = move_clear(offset_, orientation_ * wish * (speed * dt), keep_out, orientation_ * kZ);
    }
    // A body may have moved onto the camera.
    offset_ = push_out(offset_, keep_out, orientation_ * kZ);
    reanchor_to_nearest(bodies);
}

void NavigationModel::step_surface_walk(const NavAxes& in, double dt) {
    const double turn = deg(tuning_.turn_rate_deg_s) * dt;
    const double speed = speed_at(eye_height_m_);
    bool turned = false;
    if (const double yaw = in.yaw_left * turn; yaw != 0.0) {  // heading about the zenith (the walker's z)
        walker_ = walker_ * glm::angleAxis(yaw, kZ);
        turned = true;
    }
    if ((in.forward != 0.0 || in.right != 0.0) && dt > 0.0) {
        // Walking is turning the walker's frame about the body's centre: forward about its -x,
        // right about its +y, by (distance along the surface) / radius.
        const double per_radian = std::max(anchor_seen_.radius_m, 1e-3);
        const double s = speed * dt / per_radian;
        walker_ = walker_ * rotation_from_vector(glm::dvec3(-in.forward * s, in.right * s, 0.0));
        turned = true;
    }
    if (turned) walker_ = glm::normalize(walker_);
    if (in.up != 0.0 && dt > 0.0) {
        const double h = eye_height_m_ + in.up * speed * dt;
        eye_height_m_ = std::clamp(std::isfinite(h) ? h : kMaxDistance_m, tuning_.min_altitude_m, kMaxDistance_m);
    }
    if (in.pitch_up * turn != 0.0)
        look_pitch_rad_ = std::clamp(look_pitch_rad_ + in.pitch_up * turn, -kMaxPitch_rad, kMaxPitch_rad);
}

CameraPose NavigationModel::step(const NavAxes& raw, double dt_s, const std::vector<NavBody>& bodies) {
    const double dt = (std::isfinite(dt_s) && dt_s > 0.0) ? dt_s : 0.0;
    anchor_seen_ = anchor_body(bodies);  // the anchor at the new time (the camera rides with it)
    if (flight_) {
        flight_->elapsed_s += dt;
        if (flight_->elapsed_s >= flight_->duration_s) {  // arrived: orbit there
            orientation_ = flight_->q1;
            distance_m_ = flight_->d1;
            flight_.reset();
        }
        return pose(bodies);
    }
    const NavAxes in = clean(raw);
    switch (mode_) {
        case NavMode::Orbit:
            step_orbit(in, dt);
            break;
        case NavMode::FreeFly:
            step_free_fly(in, dt, bodies);
            break;
        case NavMode::SurfaceWalk:
            step_surface_walk(in, dt);
            break;
    }
    return pose(bodies);
}

}  // namespace cupola

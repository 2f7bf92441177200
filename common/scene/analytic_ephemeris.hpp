#pragma once
// A simple analytic ephemeris, good to a fraction of a degree for 1800-2050: Earth from mean
// Keplerian elements (Standish, JPL "Approximate Positions of the Planets", Table 1), the Moon on
// a circular orbit with a regressing node, Earth rotation by the IAU Earth Rotation Angle.
// World frame: equatorial J2000 axes, metres, Sun at the origin. The eclipse issue replaces it
// with a real ephemeris library.
#include "config/scene_config.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

constexpr double kAstronomicalUnit_m = 1.495978707e11;

BodyState analytic_body_state(const BodyConfig& body, double t_s_since_j2000);

}  // namespace cupola

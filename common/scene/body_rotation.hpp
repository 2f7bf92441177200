#pragma once
// Orientation of the Sun, the planets, Pluto, the Galilean moons and the Moon from the IAU Working
// Group on Cartographic Coordinates and Rotational Elements: Archinal et al. 2018 (the 2015 report),
// Tables 1 and 2 (the Galilean moons with Jupiter's J3 .. J7 terms for Io and Europa); the
// Moon from Archinal et al. 2011 (the 2009 report, Table 2, not revised in 2015). For each body,
// the north pole (alpha0, delta0) in ICRF and the prime meridian angle W, measured eastward along
// the body's equator from the node Q where it crosses the ICRF equator:
//   alpha0 = a0 + a1 T + sum a_i sin E_i,  delta0 = d0 + d1 T + sum d_i cos E_i,
//   W = W0 + Wdot d + W2 d^2 + sum w_i sin E_i,   T centuries and d days of TDB from J2000.
// Periodic terms are kept for the Moon (E1..E13) and Neptune (N); those of Mars and Jupiter are
// below 0.001 deg and left out. The Earth is not here: ERFA's Earth rotation (scene/ephemeris) is better.
//
// Body frame: +Z the north pole, +X the prime meridian on the equator, longitudes east-positive
// (atan2(y, x)), as the body maps are read (shaders/shared/sphere_view.glsl, body_map_uv).
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>

namespace cupola {

struct RotationElements {
    double pole_ra_deg = 0.0;
    double pole_dec_deg = 90.0;
    double prime_meridian_deg = 0.0;
};

// Whether iau_rotation_elements knows the body ("sun", "mercury" ... "neptune", "pluto", "moon", "io",
// "europa", "ganymede", "callisto", "titan").
bool has_iau_rotation(const std::string& body);

// The elements at t_tdb_s seconds from J2000 (TT may stand for TDB). The caller applies the light
// time: a body is seen as it was when the light left it (Jupiter turns 24 deg in 40 minutes).
// Throws std::invalid_argument naming the body when it has none.
RotationElements iau_rotation_elements(const std::string& body, double t_tdb_s);

// Body frame -> ICRS axes.
glm::dquat body_to_icrs(const RotationElements& e);

// The body-frame (east) longitude and latitude, in degrees, of the unit direction u given in ICRS axes.
glm::dvec2 body_longitude_latitude_deg(const glm::dquat& body_to_icrs, const glm::dvec3& u);

}  // namespace cupola

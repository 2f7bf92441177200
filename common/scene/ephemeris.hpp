#pragma once
// Body states for the scene from ERFA (sources and accuracy in scene/sky_positions.hpp and
// docs/ephemeris-accuracy.md). World frame: ICRS axes, metres, origin at the Sun's centre.
//
// Positions are placed for a geocentric viewer: the Earth sits at its geometric heliocentric
// position, and every other body at Earth + its apparent geocentric vector (light time, plus annual
// aberration for the Sun and planets). So the Sun is drawn where it is seen, about 20" (14 500 km)
// from the world origin, and the rendered Sun-Moon-Earth geometry is the one the eclipse
// predictions (scene/eclipse_geometry) use: the Moon's shadow falls where the eclipse tables say.
//
// Orientations map the body frame to the world frame:
//   earth: body frame = ITRS (x toward Greenwich on the equator, z to the north pole), from the
//          GCRS->ITRS matrix of eraC2t06a (UT1 from sim_time, no polar motion), transposed;
//   sun, moon, planets and Pluto: the IAU rotation elements (scene/body_rotation), at the time the
//          light left the body (light time from the Earth's centre).
#include "config/scene_config.hpp"
#include "scene/sky_positions.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// body.ephemeris is one of "sun", "earth", "moon", "mercury", ..., "neptune", "pluto", "io", "europa",
// "ganymede", "callisto", "titan"; t in seconds since
// J2000 TT. Throws std::invalid_argument for another name.
BodyState body_state(const BodyConfig& body, double t_tt_s);

// ITRS -> world (GCRS/ICRS axes) rotation of the Earth.
glm::dquat earth_orientation(double t_tt_s);

}  // namespace cupola

#pragma once
// Apparent geocentric positions of the Sun, the Moon, the planets and Pluto:
//   Earth (heliocentric and barycentric)  ERFA eraEpv00  (vs DE405: a few km, Note in epv00.c)
//   Moon (geocentric, geometric)          ERFA eraMoon98 (vs ELP/MPP02 1950-2100: RMS 2.9", worst 18.3")
//   Mercury ... Neptune, Pluto            VSOP87 and Meeus ch. 37 through libnova (scene/planet_series)
//   Io, Europa, Ganymede, Callisto        Jupiter + JPL's mean elements (scene/satellite_orbits)
// Measured against an independent ephemeris over 1900-2100 in docs/ephemeris-accuracy.md.
// "Apparent" = light-time corrected (the body where it was when the light left it), plus annual
// aberration (eraAb, the Earth's barycentric velocity) for the Sun and the planets. For the Moon
// only light time is applied: its geocentric vector is already relative to the moving Earth, so
// the annual aberration and the Earth's motion during the light time cancel. Light deflection by
// the Sun (< 0.01" more than a few degrees from it) and diurnal aberration are neglected.
// Vectors are in GCRS axes (= ICRS to within 23 mas), metres, with the light-time distance.
// TDB is taken as TT (< 2 ms apart).
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace cupola {

constexpr double kAstronomicalUnit_m = 1.495978707e11;

struct SkyPosition {
    glm::dvec3 gcrs_m{0.0};  // apparent geocentric vector, GCRS axes, metres
    double ra_deg = 0.0;     // apparent right ascension, true equator and equinox of date, [0, 360)
    double dec_deg = 0.0;    // apparent declination, true equator of date
    double distance_km = 0.0;
};

// The body names understood below: sun, moon, mercury, venus, mars, jupiter, saturn, uranus, neptune,
// pluto, io, europa, ganymede, callisto, titan.
const std::vector<std::string>& sky_body_names();

// The apparent geocentric vector alone (what searches need). Throws std::invalid_argument naming
// the body if it is not one of sky_body_names().
glm::dvec3 apparent_geocentric_m(const std::string& body, double t_tt_s);

// The astrometric geocentric vector: light time only, no aberration (ICRS axes, metres). For the
// Moon it equals the apparent one.
glm::dvec3 astrometric_geocentric_m(const std::string& body, double t_tt_s);

// The same with right ascension and declination of date (GCRS rotated by eraPnm06a, then eraC2s).
SkyPosition sky_position(const std::string& body, double t_tt_s);

// Geometric heliocentric position of the Earth's centre (eraEpv00), ICRS axes, metres.
glm::dvec3 earth_heliocentric_m(double t_tt_s);

// GCRS -> ITRS rotation at a TT instant: eraC2t06a with UT1 from sim_time (ΔT) and no polar
// motion (xp = yp = 0, below 0.5" / 15 m). itrs = gcrs_to_itrs(t) * gcrs.
glm::dmat3 gcrs_to_itrs(double t_tt_s);

}  // namespace cupola

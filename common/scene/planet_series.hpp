#pragma once
// Heliocentric positions of the planets and Pluto, from libnova's series:
//   Mercury ... Neptune: VSOP87 (Bretagnon & Francou 1988), the full series, J2000 ecliptic;
//   Pluto: Meeus 1998, ch. 37 (after Goffin, Meeus & Steyaert), valid 1885-2099.
// They replace ERFA's eraPlan94 (Simon et al. 1994), whose error reaches 75-94" for Jupiter, Saturn
// and Uranus within 1900-2100 (measured against an independent ephemeris: docs/ephemeris-accuracy.md);
// VSOP87 stays within about 1". The J2000 ecliptic is turned into ICRS axes with the IAU 2006
// obliquity of J2000 (the FK5-ICRS frame bias, 23 mas, is neglected).
//
// A full VSOP87 evaluation costs about 0.1 ms on these machines, and the apparent place needs it
// at the light-time instant: planet_heliocentric_au therefore evaluates the series on a grid of
// quarter days and interpolates a cubic through four nodes (within 1.5 km of the series, 0.003" at
// Mercury's closest). The last nodes of each planet are kept per thread, so a frame in the same
// quarter day costs four multiplications.
#include <glm/glm.hpp>

#include <string>

namespace cupola {

enum class PlanetSeries { Mercury, Venus, Mars, Jupiter, Saturn, Uranus, Neptune, Pluto };

// "mercury" ... "pluto"; throws std::invalid_argument naming the body otherwise.
PlanetSeries planet_series_from_name(const std::string& name);

// Heliocentric position (AU, ICRS axes) at d days of TT (as TDB) from J2000, straight from the series.
glm::dvec3 planet_heliocentric_series_au(PlanetSeries planet, double d);

// The same, interpolated from the series' quarter-day nodes (see above).
glm::dvec3 planet_heliocentric_au(PlanetSeries planet, double d);

}  // namespace cupola

#pragma once
// The Galilean moons' positions relative to Jupiter, from JPL's mean orbital elements referred to
// each moon's local Laplace plane (JPL Solar System Dynamics, "Planetary Satellite Mean
// Elements", epoch 1997 Jan 16.00 TT): a precessing ellipse fitted by least squares to the
// numerically integrated orbit. The argument of periapsis advances and the node regresses
// uniformly with the listed periods; the mean longitude advances at the listed mean motion n
// (360 / n is the sidereal period). The Laplace plane's pole is fixed in the ICRF; the node is
// counted from where that plane crosses the ICRF equator.
//
// A fitted ellipse leaves out the moons' mutual perturbations (the Laplace resonance of Io, Europa
// and Ganymede) and the Sun's: measured against PyEphem's independent theory in
// docs/ephemeris-accuracy.md (test_ephemeris_reference).
//
// Titan's ellipse is the same model, epoch J2000 TT, fitted by tools/fit_titan_elements.py to the
// Bureau des Longitudes' ephemeris of Saturn's moons (after the TASS 1.7 theory, Vienne & Duriez
// 1995) as PyEphem gives it for 1999-2039, on the Laplacian plane of Jacobson (1998, appendix A):
// within 4 600 km of it there (0.7" from the Earth). Its periapsis' longitude turns in 695 years
// (Jacobson's 698) and its node in 1 330 (his 1 215).
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace cupola {

// The moons known here ("io", "europa", "ganymede", "callisto", "titan") and the planet each one
// circles.
const std::vector<std::string>& satellite_names();
bool is_satellite(const std::string& name);
std::string satellite_parent(const std::string& name);  // throws std::invalid_argument for another name

// The moon's position relative to its planet's centre at t_tt_days from J2000 TT: ICRS axes,
// metres. Throws std::invalid_argument for a name that is not a satellite.
glm::dvec3 satellite_offset_m(const std::string& name, double t_tt_days);

}  // namespace cupola

#pragma once
// Disc-integrated V magnitudes of the planets from their measured phase curves: Mallama & Hilton
// 2018 ("Computing apparent planetary magnitudes for The Astronomical Almanac", Astronomy and
// Computing 25, pp. 10-24), equations 2-17:
//   Mercury (2), Venus (3, 4), Earth (5), Mars (6, 7, without the rotation and season tables of
//   +-0.06 mag), Jupiter (8, 9), Saturn's globe alone (11, 12: what its drawn disc follows) and
//   its globe and rings together (10: what Saturn as a point carries),
//   Uranus (13, 14, with its sub-latitude term), Neptune (16, 17, after 2000).
// The Moon: Allen's phase law (Allen 1973, as Krisciunas & Schaefer 1991 give it in
// their equation 9), V(1, a) = 0.21 + 0.026 a + 4e-9 a^4, a in degrees, up to 150 degrees.
// Beyond the largest phase angle each fit was made from (Mercury 170, Venus 179, Earth 170, Mars 120,
// Jupiter 130, Saturn 150, Uranus 154, Neptune 133.14, Moon 150 deg) the curve goes on as a Lambert sphere's
// from the value there, so it stays continuous and finite up to 180 deg.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <optional>
#include <string>

namespace cupola {

// The apparent V magnitude of the Sun seen from 1 AU (Allen's Astrophysical Quantities, 4th ed.).
constexpr double kSunMagnitudeV = -26.74;

struct PlanetGeometry {
    double sun_distance_au = 1.0;       // r: the planet from the Sun
    double observer_distance_au = 1.0;  // Delta: the planet from the observer
    double phase_deg = 0.0;             // Sun - planet - observer
    double sub_sun_latitude_deg = 0.0;  // on the planet (Uranus' term)
    double sub_observer_latitude_deg = 0.0;
};

// The geometry of a body at body_m turned by `orientation` (its pole its +z), lit by the Sun at
// sun_m and seen from observer_m (world positions, double).
PlanetGeometry planet_geometry(const glm::dvec3& body_m, const glm::dquat& orientation, const glm::dvec3& sun_m,
                               const glm::dvec3& observer_m);

// A measured phase curve: the largest phase angle of its data, and the radius of the body it was
// measured on (a scene body of another size scales its light by the square of the ratio).
struct PhaseCurve {
    const char* planet;
    double max_phase_deg;
    double radius_m;
};
// The curve of the planet named by its ephemeris; null for a body without one.
const PhaseCurve* find_phase_curve(const std::string& planet);

// V of the planet named by its ephemeris ("mercury" ... "neptune"); none for a body without a
// fitted curve (Pluto, the moons other than ours: "moon" has Allen's).
std::optional<double> planet_magnitude_v(const std::string& planet, const PlanetGeometry& g);

// The irradiance a body with a measured phase curve sends to its observer, over the Sun's
// irradiance at 1 AU: the curve's magnitude as a flux relative to the Sun's, for a body of
// radius_m (the curve's body scaled by the square of the ratio); none without a curve. with_rings:
// Saturn's globe and rings together (saturn_with_rings_magnitude_v).
std::optional<double> phase_curve_irradiance_ratio(const std::string& planet, double radius_m, const PlanetGeometry& g,
                                                   bool with_rings = false);

// Whether a body's point light is its globe's and rings' together (a ringed Saturn: its rings'
// magnitude is measured) rather than its globe's alone. The slaves' points and the master's
// exposure both take it, so that both see the same light.
bool magnitude_includes_rings(const std::string& planet, bool has_rings);

// Saturn's globe and rings together (Mallama & Hilton 2018, equation 10, fitted for phase angles
// up to 6.5 deg and the rings opened by up to 27 deg): V(1, a) = -8.914 - 1.825 sin b + 0.026 a
// - 0.378 sin b exp(-2.25 a), b = |g.sub_observer_latitude_deg| (clamped to 27 deg). Past 6.5 deg the
// rings keep the share of the light they have there, and the globe follows its own curve. Never
// fainter than the globe alone (nearly edge-on, below b = 4 deg, the fit is).
double saturn_with_rings_magnitude_v(const PlanetGeometry& g);

// A Lambert sphere's phase function (sin a + (pi - a) cos a) / pi: 1 at full phase.
double lambert_phase(double phase_rad);

// A Lommel-Seeliger sphere's: 1 - sin(a/2) tan(a/2) ln(cot(a/4)), 1 at full phase. The integral of
// 2 cos_i cos_e / (cos_i + cos_e) over the lit, visible disc is pi times it.
double lommel_seeliger_phase(double phase_rad);

}  // namespace cupola

#include "scene/planet_magnitude.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene/sky_positions.hpp"

namespace cupola {

namespace {

double poly(double a, std::initializer_list<double> c) {  // c0 + c1 a + c2 a^2 + ...
    double s = 0.0, p = 1.0;
    for (double k : c) s += k * p, p *= a;
    return s;
}

// V(1, a): the magnitude at 1 AU from the Sun and the observer, a in degrees within the fit.
double mercury(double a) {
    return poly(a, {-0.613, 6.3280e-02, -1.6336e-03, 3.3644e-05, -3.4265e-07, 1.6893e-09, -3.0334e-12});
}
double venus(double a) {
    if (a < 163.7) return poly(a, {-4.384, -1.044e-03, 3.687e-04, -2.814e-06, 8.938e-09});
    return poly(a, {236.05828, -2.81914, 8.39034e-03});
}
double earth(double a) { return poly(a, {-3.99, -1.060e-03, 2.054e-04}); }
double mars(double a) {
    return a <= 50.0 ? poly(a, {-1.601, 2.267e-02, -1.302e-04}) : poly(a, {-0.367, -0.02573, 3.445e-04});
}
double jupiter(double a) {
    if (a <= 12.0) return poly(a, {-9.395, -3.7e-04, 6.16e-04});
    return -9.428 - 2.5 * std::log10(poly(a / 180.0, {1.0, -1.507, -0.363, -0.062, 2.809, -1.876}));
}
double saturn_globe(double a) {
    if (a <= 6.5) return poly(a, {-8.95, -3.7e-04, 6.16e-04});
    return poly(a, {-8.94, 2.446e-04, 2.672e-04, -1.506e-06, 4.767e-09});
}
double uranus(double a, const PlanetGeometry& g) {
    const double sub_lat = 0.5 * (std::abs(g.sub_sun_latitude_deg) + std::abs(g.sub_observer_latitude_deg));
    const double v = -7.110 - 0.00084 * sub_lat;
    return a <= 3.1 ? v : v + 6.587e-3 * a + 1.045e-4 * a * a;
}
double neptune(double a) { return a <= 1.9 ? -7.00 : -7.00 + 7.944e-3 * a + 9.617e-5 * a * a; }
// The Moon: Allen's V(1, 0) = +0.21 and his phase law 0.026 a + 4e-9 a^4 (Allen 1973, the Moon's photometry;
// Krisciunas & Schaefer 1991, equation 9).
double moon(double a) { return 0.21 + 0.026 * a + 4.0e-9 * a * a * a * a; }

// The equatorial radii (Archinal et al. 2018, Table 4; the Moon's mean radius) of the bodies the
// curves were measured on.
constexpr PhaseCurve kCurves[] = {
    {"mercury", 170.0, 2.44053e6}, {"venus", 179.0, 6.0518e6},    {"earth", 170.0, 6.378137e6},
    {"mars", 120.0, 3.39619e6},    {"jupiter", 130.0, 7.1492e7},  {"saturn", 150.0, 6.0268e7},
    {"uranus", 154.0, 2.5559e7},   {"neptune", 133.14, 2.4764e7}, {"moon", 150.0, 1.7374e6}};

double unit_magnitude(const std::string& p, double a, const PlanetGeometry& g) {
    if (p == "mercury") return mercury(a);
    if (p == "venus") return venus(a);
    if (p == "earth") return earth(a);
    if (p == "mars") return mars(a);
    if (p == "jupiter") return jupiter(a);
    if (p == "saturn") return saturn_globe(a);
    if (p == "uranus") return uranus(a, g);
    if (p == "moon") return moon(a);
    return neptune(a);
}

}  // namespace

double lambert_phase(double a) { return (std::sin(a) + (std::numbers::pi - a) * std::cos(a)) / std::numbers::pi; }

double lommel_seeliger_phase(double a) {
    if (a <= 0.0) return 1.0;
    if (a >= std::numbers::pi) return 0.0;
    return 1.0 - std::sin(0.5 * a) * std::tan(0.5 * a) * std::log(1.0 / std::tan(0.25 * a));
}

const PhaseCurve* find_phase_curve(const std::string& planet) {
    for (const PhaseCurve& c : kCurves)
        if (planet == c.planet) return &c;
    return nullptr;
}

std::optional<double> planet_magnitude_v(const std::string& planet, const PlanetGeometry& g) {
    const PhaseCurve* curve = find_phase_curve(planet);
    if (!curve) return std::nullopt;
    const double a = std::clamp(g.phase_deg, 0.0, 180.0), fit = std::min(a, curve->max_phase_deg);
    double v = unit_magnitude(planet, fit, g) + 5.0 * std::log10(g.sun_distance_au * g.observer_distance_au);
    if (a > fit) {
        constexpr double deg = std::numbers::pi / 180.0;
        const double ratio = std::max(lambert_phase(a * deg), 1e-12) / lambert_phase(fit * deg);
        v -= 2.5 * std::log10(ratio);
    }
    return v;
}

PlanetGeometry planet_geometry(const glm::dvec3& body_m, const glm::dquat& orientation, const glm::dvec3& sun_m,
                               const glm::dvec3& observer_m) {
    const glm::dvec3 to_sun = sun_m - body_m, to_observer = observer_m - body_m;
    const glm::dvec3 pole = orientation * glm::dvec3(0.0, 0.0, 1.0);
    PlanetGeometry g;
    g.sun_distance_au = glm::length(to_sun) / kAstronomicalUnit_m;
    g.observer_distance_au = glm::length(to_observer) / kAstronomicalUnit_m;
    g.phase_deg = glm::degrees(std::atan2(glm::length(glm::cross(to_sun, to_observer)), glm::dot(to_sun, to_observer)));
    g.sub_sun_latitude_deg = glm::degrees(std::asin(std::clamp(glm::dot(pole, glm::normalize(to_sun)), -1.0, 1.0)));
    g.sub_observer_latitude_deg =
        glm::degrees(std::asin(std::clamp(glm::dot(pole, glm::normalize(to_observer)), -1.0, 1.0)));
    return g;
}

std::optional<double> phase_curve_irradiance_ratio(const std::string& planet, double radius_m, const PlanetGeometry& g,
                                                   bool with_rings) {
    const PhaseCurve* curve = find_phase_curve(planet);
    if (!curve) return std::nullopt;
    const double size = radius_m / curve->radius_m;
    const double v = with_rings ? saturn_with_rings_magnitude_v(g) : *planet_magnitude_v(planet, g);
    return size * size * std::pow(10.0, -0.4 * (v - kSunMagnitudeV));
}

bool magnitude_includes_rings(const std::string& planet, bool has_rings) { return has_rings && planet == "saturn"; }

double saturn_with_rings_magnitude_v(const PlanetGeometry& g) {
    const double fit = std::clamp(g.phase_deg, 0.0, 6.5);
    const double sin_b = std::sin(glm::radians(std::min(std::abs(g.sub_observer_latitude_deg), 27.0)));
    const double together = -8.914 - 1.825 * sin_b + 0.026 * fit - 0.378 * sin_b * std::exp(-2.25 * fit);
    // Past the fit the whole follows the globe's curve from there (the distances cancel).
    PlanetGeometry at_fit = g;
    at_fit.phase_deg = fit;
    const double globe = *planet_magnitude_v("saturn", g),
                 globe_past_fit = globe - *planet_magnitude_v("saturn", at_fit);
    // Nearly edge-on the fit gives less light than the globe's own curve (it does not meet it at
    // b = 0): the rings never darken the planet.
    return std::min(together + 5.0 * std::log10(g.sun_distance_au * g.observer_distance_au) + globe_past_fit, globe);
}

}  // namespace cupola

#include "scene/analytic_ephemeris.hpp"

#include <erfa.h>
#include <erfam.h>

#include <cmath>

#include "scene/sim_time.hpp"

namespace cupola {

namespace {
constexpr double kObliquityJ2000 = 23.43928 * M_PI / 180.0;

glm::dvec3 ecliptic_to_equatorial(const glm::dvec3& e) {
    const double c = std::cos(kObliquityJ2000), s = std::sin(kObliquityJ2000);
    return {e.x, c * e.y - s * e.z, s * e.y + c * e.z};
}

double deg(double d) { return d * M_PI / 180.0; }

// Heliocentric ecliptic position of the Earth-Moon barycentre, metres.
glm::dvec3 earth_heliocentric_ecliptic(double T) {
    const double a = (1.00000261 + 0.00000562 * T) * kAstronomicalUnit_m;
    const double e = 0.01671123 - 0.00004392 * T;
    const double I = deg(-0.00001531 - 0.01294668 * T);
    const double L = deg(100.46457166 + 35999.37244981 * T);
    const double varpi = deg(102.93768193 + 0.32327364 * T);
    const double Omega = 0.0;
    const double omega = varpi - Omega;
    double M = std::remainder(L - varpi, 2.0 * M_PI);
    double E = M + e * std::sin(M);
    for (int i = 0; i < 8; ++i) E -= (E - e * std::sin(E) - M) / (1.0 - e * std::cos(E));
    const double xp = a * (std::cos(E) - e), yp = a * std::sqrt(1 - e * e) * std::sin(E);
    const double co = std::cos(omega), so = std::sin(omega), cO = std::cos(Omega), sO = std::sin(Omega);
    const double cI = std::cos(I), sI = std::sin(I);
    return {(co * cO - so * sO * cI) * xp + (-so * cO - co * sO * cI) * yp,
            (co * sO + so * cO * cI) * xp + (-so * sO + co * cO * cI) * yp, (so * sI) * xp + (co * sI) * yp};
}

// Geocentric ecliptic position of the Moon: circular orbit, mean elements (Meeus ch. 47 leading terms).
glm::dvec3 moon_geocentric_ecliptic(double T) {
    const double r = 3.844e8;
    const double i = deg(5.145);
    const double Omega = deg(125.04452 - 1934.136261 * T);
    const double L = deg(218.3164477 + 481267.88123421 * T);
    const double u = L - Omega;
    return {r * (std::cos(Omega) * std::cos(u) - std::sin(Omega) * std::sin(u) * std::cos(i)),
            r * (std::sin(Omega) * std::cos(u) + std::cos(Omega) * std::sin(u) * std::cos(i)),
            r * std::sin(u) * std::sin(i)};
}

glm::dquat rotation_about_z(double angle) { return glm::angleAxis(angle, glm::dvec3(0, 0, 1)); }
}  // namespace

BodyState analytic_body_state(const BodyConfig& body, double t) {
    const double T = julian_centuries(t);
    BodyState s;
    s.id = body.id;
    if (body.ephemeris == "sun") {
        s.position_m = glm::dvec3(0.0);
        s.orientation = glm::dquat(1, 0, 0, 0);
    } else if (body.ephemeris == "earth") {
        s.position_m = ecliptic_to_equatorial(earth_heliocentric_ecliptic(T));
        // Earth Rotation Angle (UT1 taken as TT here: the ~69 s difference is below this model's error).
        const double jd = ERFA_DJ00 + t / ERFA_DAYSEC;
        s.orientation = rotation_about_z(eraEra00(jd, 0.0));
    } else {  // moon
        const glm::dvec3 earth = ecliptic_to_equatorial(earth_heliocentric_ecliptic(T));
        const glm::dvec3 rel = ecliptic_to_equatorial(moon_geocentric_ecliptic(T));
        s.position_m = earth + rel;
        // Tidally locked: the body's +X (prime meridian) faces the Earth, +Z near the ecliptic pole.
        const glm::dvec3 x = glm::normalize(-rel);
        const glm::dvec3 pole = ecliptic_to_equatorial(glm::dvec3(0, 0, 1));
        const glm::dvec3 y = glm::normalize(glm::cross(pole, x));
        const glm::dvec3 z = glm::cross(x, y);
        s.orientation = glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
    }
    return s;
}

}  // namespace cupola

#include "scene/ephemeris.hpp"

#include <erfa.h>
#include <erfam.h>

#include <cmath>

namespace cupola {

glm::dquat earth_orientation(double t_tt_s) {
    return glm::normalize(glm::quat_cast(glm::transpose(gcrs_to_itrs(t_tt_s))));
}

BodyState body_state(const BodyConfig& body, double t_tt_s) {
    BodyState s;
    s.id = body.id;
    const glm::dvec3 earth = earth_heliocentric_m(t_tt_s);
    if (body.ephemeris == "earth") {
        s.position_m = earth;
        s.orientation = earth_orientation(t_tt_s);
        return s;
    }
    const glm::dvec3 rel = apparent_geocentric_m(body.ephemeris, t_tt_s);
    s.position_m = earth + rel;
    if (body.ephemeris == "moon") {
        // Tidally locked: the body's +X (prime meridian) faces the Earth, +Z near the ecliptic pole.
        const double eps = eraObl06(ERFA_DJ00, 0.0);  // mean obliquity of J2000
        const glm::dvec3 pole(0.0, -std::sin(eps), std::cos(eps));
        const glm::dvec3 x = glm::normalize(-rel);
        const glm::dvec3 y = glm::normalize(glm::cross(pole, x));
        const glm::dvec3 z = glm::cross(x, y);
        s.orientation = glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
    }
    return s;
}

}  // namespace cupola

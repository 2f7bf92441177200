#include "scene/ephemeris.hpp"

#include "scene/body_rotation.hpp"

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
    if (has_iau_rotation(body.ephemeris)) {
        // Turned as it was when the light left it.
        const double light_time_s = glm::length(rel) / ERFA_CMPS;
        s.orientation = body_to_icrs(iau_rotation_elements(body.ephemeris, t_tt_s - light_time_s));
    }
    return s;
}

}  // namespace cupola

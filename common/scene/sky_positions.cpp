#include "scene/sky_positions.hpp"

#include <erfa.h>
#include <erfam.h>

#include <cmath>
#include <stdexcept>

#include "scene/planet_series.hpp"
#include "scene/satellite_orbits.hpp"
#include "scene/sim_time.hpp"

namespace cupola {

namespace {

constexpr double kLightAuPerDay = ERFA_CMPS * ERFA_DAYSEC / ERFA_DAU;

glm::dvec3 vec(const double p[3]) { return {p[0], p[1], p[2]}; }

// Earth state from eraEpv00 at TT (as TDB) day offset d from J2000: AU, AU/day.
struct EarthState {
    glm::dvec3 helio, bary, bary_velocity;
};
EarthState earth_state(double d) {
    double pvh[2][3], pvb[2][3];
    eraEpv00(ERFA_DJ00, d, pvh, pvb);
    return {vec(pvh[0]), vec(pvb[0]), vec(pvb[1])};
}

// Body index: 0 Sun, 1 Moon, 2.. the planets and Pluto (planet_series).
int body_index(const std::string& name) {
    const auto& names = sky_body_names();
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return int(i);
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown body '" + name + "' (one of: " + list + ")");
}

constexpr int kFirstSatellite = 10;  // after the Sun, the Moon, the planets and Pluto

// Barycentric position (AU) of the Sun, a planet or a planet's moon at day offset d.
glm::dvec3 barycentric_au(int index, double d) {
    if (index >= kFirstSatellite) {
        const std::string& name = sky_body_names()[static_cast<size_t>(index)];
        return barycentric_au(body_index(satellite_parent(name)), d) +
               satellite_offset_m(name, d) / kAstronomicalUnit_m;
    }
    const EarthState e = earth_state(d);
    const glm::dvec3 sun = e.bary - e.helio;
    if (index == 0) return sun;
    return sun + planet_heliocentric_au(static_cast<PlanetSeries>(index - 2), d);
}

}  // namespace

const std::vector<std::string>& sky_body_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n = {"sun",     "moon",   "mercury", "venus",   "mars",
                                      "jupiter", "saturn", "uranus",  "neptune", "pluto"};
        for (const auto& moon : satellite_names()) n.push_back(moon);
        return n;
    }();
    return names;
}

glm::dvec3 astrometric_geocentric_m(const std::string& body, double t_tt_s) {
    const int index = body_index(body);
    const double d = t_tt_s / ERFA_DAYSEC;
    if (index == 1) {
        // Moon: geocentric position at t - light time (two iterations converge to < 1 mm).
        double pv[2][3], tau = 0.0;
        for (int i = 0; i < 3; ++i) {
            eraMoon98(ERFA_DJ00, d - tau, pv);
            tau = glm::length(vec(pv[0])) / kLightAuPerDay;
        }
        return vec(pv[0]) * kAstronomicalUnit_m;
    }
    // Sun and planets: the body at t - light time, the Earth at t.
    const EarthState earth = earth_state(d);
    glm::dvec3 p(0.0);
    double tau = 0.0;
    for (int i = 0; i < 3; ++i) {
        p = barycentric_au(index, d - tau) - earth.bary;
        tau = glm::length(p) / kLightAuPerDay;
    }
    return p * kAstronomicalUnit_m;
}

glm::dvec3 apparent_geocentric_m(const std::string& body, double t_tt_s) {
    const glm::dvec3 p = astrometric_geocentric_m(body, t_tt_s);
    if (body == "moon") return p;
    // Annual aberration with the Earth's barycentric velocity.
    const EarthState earth = earth_state(t_tt_s / ERFA_DAYSEC);
    const double dist = glm::length(p);
    double pnat[3] = {p.x / dist, p.y / dist, p.z / dist}, ppr[3];
    const glm::dvec3 v = earth.bary_velocity / kLightAuPerDay;  // in units of c
    double vc[3] = {v.x, v.y, v.z};
    eraAb(pnat, vc, glm::length(earth.helio), std::sqrt(1.0 - glm::dot(v, v)), ppr);
    return vec(ppr) * dist;
}

SkyPosition sky_position(const std::string& body, double t_tt_s) {
    SkyPosition s;
    s.gcrs_m = apparent_geocentric_m(body, t_tt_s);
    const JulianDate tt = tt_julian_date(t_tt_s);
    double rnpb[3][3], p[3] = {s.gcrs_m.x, s.gcrs_m.y, s.gcrs_m.z}, q[3], ra, dec;
    eraPnm06a(tt.jd1, tt.jd2, rnpb);  // GCRS -> true equator and equinox of date
    eraRxp(rnpb, p, q);
    eraC2s(q, &ra, &dec);
    s.ra_deg = eraAnp(ra) * ERFA_DR2D;
    s.dec_deg = dec * ERFA_DR2D;
    s.distance_km = glm::length(s.gcrs_m) / 1000.0;
    return s;
}

glm::dvec3 earth_heliocentric_m(double t_tt_s) { return earth_state(t_tt_s / ERFA_DAYSEC).helio * kAstronomicalUnit_m; }

glm::dmat3 gcrs_to_itrs(double t_tt_s) {
    const JulianDate tt = tt_julian_date(t_tt_s), ut1 = tt_to_ut1_jd(t_tt_s);
    double r[3][3];
    eraC2t06a(tt.jd1, tt.jd2, ut1.jd1, ut1.jd2, 0.0, 0.0, r);
    // ERFA matrices are row-major (r[row][col]); glm is column-major (m[col][row]).
    glm::dmat3 m;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) m[col][row] = r[row][col];
    return m;
}

}  // namespace cupola

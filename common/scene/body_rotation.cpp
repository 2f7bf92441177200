#include "scene/body_rotation.hpp"

#include <erfa.h>
#include <erfam.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace cupola {

namespace {

// One periodic term: amplitudes (deg) on sin E (alpha0), cos E (delta0), sin E (W) of the angle
// E = e0 + e1 T (deg, T in centuries).
struct PeriodicTerm {
    double e0, e1, ra, dec, pm;
};

struct IauModel {
    const char* body;
    double a0, a1, d0, d1, w0, wdot, w2;
    std::vector<PeriodicTerm> terms;
};

// The Moon's E1..E13 (Archinal et al. 2011, Table 2), as rates per century.
std::vector<PeriodicTerm> moon_terms() {
    return {{125.045, -1935.5364525, -3.8787, 1.5419, 3.5610},
            {250.089, -3871.0729050, -0.1204, 0.0239, 0.1208},
            {260.008, 475263.3328725, 0.0700, -0.0278, -0.0642},
            {176.625, 487269.6299850, -0.0172, 0.0068, 0.0158},
            {357.529, 35999.0509575, 0.0, 0.0, 0.0252},
            {311.589, 964468.4993100, 0.0072, -0.0029, -0.0066},
            {134.963, 477198.8693250, 0.0, 0.0009, -0.0047},
            {276.617, 12006.3007650, 0.0, 0.0, -0.0046},
            {34.226, 63863.5132425, 0.0, 0.0, 0.0028},
            {15.134, -5806.6093575, -0.0052, 0.0008, 0.0052},
            {119.743, 131.8406400, 0.0, 0.0, 0.0040},
            {239.961, 6003.1503825, 0.0, 0.0, 0.0019},
            {25.053, 473327.7964200, 0.0043, -0.0009, -0.0044}};
}

const std::vector<IauModel>& models() {
    static const std::vector<IauModel> m = {
        {"sun", 286.13, 0.0, 63.87, 0.0, 84.176, 14.1844000, 0.0, {}},
        {"mercury", 281.0103, -0.0328, 61.4155, -0.0049, 329.5988, 6.1385108, 0.0, {}},
        {"venus", 272.76, 0.0, 67.16, 0.0, 160.20, -1.4813688, 0.0, {}},
        {"mars", 317.269202, -0.10927547, 54.432516, -0.05827105, 176.049863, 350.891982443297, 0.0, {}},
        {"jupiter", 268.056595, -0.006499, 64.495303, 0.002413, 284.95, 870.5360000, 0.0, {}},
        {"saturn", 40.589, -0.036, 83.537, -0.004, 38.90, 810.7939024, 0.0, {}},
        {"uranus", 257.311, 0.0, -15.175, 0.0, 203.81, -501.1600928, 0.0, {}},
        // Neptune's N = 357.85 + 52.316 T: alpha0 + 0.70 sin N, delta0 - 0.51 cos N, W - 0.48 sin N.
        {"neptune", 299.36, 0.0, 43.46, 0.0, 249.978, 541.1397757, 0.0, {{357.85, 52.316, 0.70, -0.51, -0.48}}},
        {"pluto", 132.993, 0.0, -6.163, 0.0, 302.695, 56.3625225, 0.0, {}},
        {"moon", 269.9949, 0.0031, 66.5392, 0.0130, 38.3213, 13.17635815, -1.4e-12, moon_terms()},
        // The Galilean moons, with Jupiter's J3 .. J7 terms for Io and Europa (up to 1.1 deg); those
        // of Ganymede and Callisto (up to 0.6 deg) are left out.
        {"io",
         268.05,
         -0.009,
         64.50,
         0.003,
         200.39,
         203.4889538,
         0.0,
         {{283.90, 4850.7, 0.094, 0.040, -0.085}, {355.80, 1191.3, 0.024, 0.011, -0.022}}},
        {"europa",
         268.08,
         -0.009,
         64.51,
         0.003,
         36.022,
         101.3747235,
         0.0,
         {{355.80, 1191.3, 1.086, 0.468, -0.980},
          {119.90, 262.1, 0.060, 0.026, -0.054},
          {229.80, 64.3, 0.015, 0.007, -0.014},
          {352.25, 2382.6, 0.009, 0.002, -0.008}}},
        {"ganymede", 268.20, -0.009, 64.57, 0.003, 44.064, 50.3176081, 0.0, {}},
        {"callisto", 268.72, -0.009, 64.83, 0.003, 259.51, 21.5710715, 0.0, {}},
        // Titan (Archinal et al. 2018): a fixed pole, synchronous rotation.
        {"titan", 39.4827, 0.0, 83.4279, 0.0, 186.5855, 22.5769768, 0.0, {}},
    };
    return m;
}

const IauModel* find_model(const std::string& body) {
    for (const auto& m : models())
        if (body == m.body) return &m;
    return nullptr;
}

}  // namespace

bool has_iau_rotation(const std::string& body) { return find_model(body) != nullptr; }

RotationElements iau_rotation_elements(const std::string& body, double t_tdb_s) {
    const IauModel* m = find_model(body);
    if (!m) throw std::invalid_argument("no IAU rotation elements for body '" + body + "'");
    const double d = t_tdb_s / ERFA_DAYSEC, T = d / ERFA_DJC;
    RotationElements e{m->a0 + m->a1 * T, m->d0 + m->d1 * T, m->w0 + m->wdot * d + m->w2 * d * d};
    for (const auto& p : m->terms) {
        const double E = (p.e0 + p.e1 * T) * ERFA_DD2R;
        e.pole_ra_deg += p.ra * std::sin(E);
        e.pole_dec_deg += p.dec * std::cos(E);
        e.prime_meridian_deg += p.pm * std::sin(E);
    }
    e.prime_meridian_deg = std::fmod(e.prime_meridian_deg, 360.0);
    return e;
}

glm::dquat body_to_icrs(const RotationElements& e) {
    const glm::dvec3 z(0.0, 0.0, 1.0), x(1.0, 0.0, 0.0);
    const glm::dquat node = glm::angleAxis((e.pole_ra_deg + 90.0) * ERFA_DD2R, z);
    const glm::dquat tilt = glm::angleAxis((90.0 - e.pole_dec_deg) * ERFA_DD2R, x);
    const glm::dquat spin = glm::angleAxis(e.prime_meridian_deg * ERFA_DD2R, z);
    return glm::normalize(node * tilt * spin);
}

glm::dvec2 body_longitude_latitude_deg(const glm::dquat& body_to_icrs, const glm::dvec3& u) {
    const glm::dvec3 b = glm::conjugate(body_to_icrs) * glm::normalize(u);
    return {std::atan2(b.y, b.x) * ERFA_DR2D, std::asin(std::clamp(b.z, -1.0, 1.0)) * ERFA_DR2D};
}

}  // namespace cupola

#include "scene/satellite_orbits.hpp"

#include <cmath>
#include <stdexcept>

namespace cupola {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kJulianYear_days = 365.25;
// JPL's Galilean table: 1997 Jan 16.00 TT (JD 2450464.5) in days from J2000 TT (JD 2451545.0).
constexpr double kJplJupiterEpoch_days = 2450464.5 - 2451545.0;

// One row: a (km), e, omega, M, i, node (deg at the epoch, days from J2000 TT), n (deg/day), the
// periods of the periapsis' advance and the node's regression (years), the Laplace plane's pole.
struct MeanElements {
    const char* name;
    const char* parent;
    double epoch_days;
    double a_km, e, arg_periapsis_deg, mean_anomaly_deg, inclination_deg, node_deg, n_deg_per_day;
    double periapsis_period_yr, node_period_yr, pole_ra_deg, pole_dec_deg;
};

const std::vector<MeanElements>& table() {
    static const std::vector<MeanElements> t = {
        {"io", "jupiter", kJplJupiterEpoch_days, 421800.0, 0.0041, 84.129, 342.021, 0.036, 43.977, 203.4889583, 1.625,
         7.420, 268.057, 64.495},
        {"europa", "jupiter", kJplJupiterEpoch_days, 671100.0, 0.0094, 88.970, 171.016, 0.466, 219.106, 101.3747242,
         1.394, 30.184, 268.084, 64.506},
        {"ganymede", "jupiter", kJplJupiterEpoch_days, 1070400.0, 0.0013, 192.417, 317.540, 0.177, 63.552, 50.3176072,
         63.549, 132.654, 268.168, 64.543},
        {"callisto", "jupiter", kJplJupiterEpoch_days, 1882700.0, 0.0074, 52.643, 181.408, 0.192, 298.848, 21.5710728,
         205.75, 338.82, 268.639, 64.749},
        // Titan: fitted by tools/fit_titan_elements.py to the Bureau des Longitudes' ephemeris (TASS
        // 1.7, Vienne & Duriez 1995) over 1999-2039, epoch J2000 TT, on the Laplacian plane of
        // Jacobson (1998, appendix A).
        {"titan", "saturn", 0.0, 1221870.0, 0.0287208, 338.750844, 163.602545, 0.58458, 225.231328, 22.5769736, 456.513,
         1330.53, 40.581056, 83.225166},
    };
    return t;
}

const MeanElements& find(const std::string& name) {
    for (const auto& m : table())
        if (name == m.name) return m;
    throw std::invalid_argument("no satellite orbit for '" + name + "' (io, europa, ganymede, callisto or titan)");
}

// Eccentric anomaly from the mean anomaly (radians), Newton's method; e is below 0.03 here.
double eccentric_anomaly(double mean_anomaly, double e) {
    double ecc = mean_anomaly;
    for (int i = 0; i < 8; ++i) ecc -= (ecc - e * std::sin(ecc) - mean_anomaly) / (1.0 - e * std::cos(ecc));
    return ecc;
}

glm::dmat3 rot_z(double a) {  // column-major: rotates a vector by a about +z
    return glm::dmat3(std::cos(a), std::sin(a), 0.0, -std::sin(a), std::cos(a), 0.0, 0.0, 0.0, 1.0);
}
glm::dmat3 rot_x(double a) {
    return glm::dmat3(1.0, 0.0, 0.0, 0.0, std::cos(a), std::sin(a), 0.0, -std::sin(a), std::cos(a));
}

}  // namespace

const std::vector<std::string>& satellite_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const auto& m : table()) n.emplace_back(m.name);
        return n;
    }();
    return names;
}

bool is_satellite(const std::string& name) {
    for (const auto& m : table())
        if (name == m.name) return true;
    return false;
}

std::string satellite_parent(const std::string& name) { return find(name).parent; }

glm::dvec3 satellite_offset_m(const std::string& name, double t_tt_days) {
    const MeanElements& m = find(name);
    const double dt = t_tt_days - m.epoch_days;
    const double periapsis_rate = 360.0 / (m.periapsis_period_yr * kJulianYear_days);
    const double node_rate = -360.0 / (m.node_period_yr * kJulianYear_days);  // the node regresses
    const double omega = (m.arg_periapsis_deg + periapsis_rate * dt) * kDeg;
    const double node = (m.node_deg + node_rate * dt) * kDeg;
    // n is the mean longitude's rate: the mean anomaly's is n less the periapsis' longitude's.
    const double mean_anomaly =
        std::remainder((m.mean_anomaly_deg + (m.n_deg_per_day - periapsis_rate - node_rate) * dt) * kDeg,
                       2.0 * 3.14159265358979323846);
    const double ecc = eccentric_anomaly(mean_anomaly, m.e);
    const double a_m = m.a_km * 1000.0;
    const glm::dvec3 in_orbit(a_m * (std::cos(ecc) - m.e), a_m * std::sqrt(1.0 - m.e * m.e) * std::sin(ecc), 0.0);
    // Orbit plane -> Laplace plane (periapsis, inclination, node) -> ICRS (the plane's node on the
    // ICRF equator lies 90 degrees from its pole's right ascension, its tilt is 90 - declination).
    const glm::dmat3 to_laplace = rot_z(node) * rot_x(m.inclination_deg * kDeg) * rot_z(omega);
    const glm::dmat3 to_icrs = rot_z((m.pole_ra_deg + 90.0) * kDeg) * rot_x((90.0 - m.pole_dec_deg) * kDeg);
    return to_icrs * (to_laplace * in_orbit);
}

}  // namespace cupola

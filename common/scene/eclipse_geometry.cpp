#include "scene/eclipse_geometry.hpp"

#include <erfa.h>
#include <erfam.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "scene/sim_time.hpp"
#include "scene/sky_positions.hpp"

namespace cupola {

namespace {

constexpr double kHour = 3600.0;
constexpr double kScanStep_s = 3.0 * kHour;             // new/full moon scan step
constexpr double kScanSpan_s = 2.0 * 365.25 * 86400.0;  // give up after two years
constexpr double kPeakWindow_s = 6.0 * kHour;           // greatest eclipse within this of syzygy
constexpr double kEclipseLimit_rad = 1.7 * ERFA_DD2R;   // no eclipse of either kind beyond this

struct SunMoon {
    glm::dvec3 sun, moon;  // apparent geocentric, GCRS, metres
};
SunMoon sun_moon(double t) { return {apparent_geocentric_m("sun", t), apparent_geocentric_m("moon", t)}; }

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
    return 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(glm::normalize(a) - glm::normalize(b))));
}

// Offset from the Earth's centre to the closest point of the line through p along unit a.
glm::dvec3 axis_offset(const glm::dvec3& p, const glm::dvec3& a) { return p - glm::dot(p, a) * a; }

// Golden-section search for the minimum of a unimodal f on [a, b], to an interval below tol.
template <class F>
double minimise(F f, double a, double b, double tol) {
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
    while (b - a > tol) {
        if (fc < fd) {
            b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
        } else {
            a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
        }
    }
    return 0.5 * (a + b);
}

// Where the line p + s a (ITRS, metres) first meets the WGS84 ellipsoid, coming from p; if it
// misses, the surface point closest to the line. Scaling z by a/b turns the ellipsoid into a sphere.
std::pair<glm::dvec3, bool> axis_surface_point(glm::dvec3 p, glm::dvec3 a) {
    const double k = 1.0 / (1.0 - kEarthFlattening), r = kEarthEquatorialRadius_m;
    p.z *= k, a.z *= k;
    const double A = glm::dot(a, a), B = glm::dot(p, a), C = glm::dot(p, p) - r * r, disc = B * B - A * C;
    glm::dvec3 q;
    if (disc >= 0.0) {
        q = p + ((-B - std::sqrt(disc)) / A) * a;
    } else {
        q = p - (B / A) * a;
        q *= r / glm::length(q);
    }
    q.z /= k;
    return {q, disc >= 0.0};
}

struct Local {
    std::string type = "none";
    double magnitude = 0.0;
};

// What an observer at GCRS point p sees of the Sun and Moon.
Local local_solar(const SunMoon& sm, const glm::dvec3& p) {
    const glm::dvec3 s = sm.sun - p, m = sm.moon - p;
    const double rs = std::asin(kSunRadius_m / glm::length(s)), rm = std::asin(kMoonRadius_m / glm::length(m));
    const double sep = angle_between(s, m);
    if (sep <= rm - rs) return {"total", rm / rs};
    if (sep <= rs - rm) return {"annular", rm / rs};
    if (sep < rs + rm) return {"partial", (rs + rm - sep) / (2.0 * rs)};
    return {};
}

// Signed length of an axis offset in Earth equatorial radii: + when it points north.
double signed_gamma(const glm::dvec3& offset, const glm::dmat3& gcrs_to_itrs_m) {
    const double g = glm::length(offset) / kEarthEquatorialRadius_m;
    return (gcrs_to_itrs_m * offset).z >= 0.0 ? g : -g;
}

glm::dvec3 solar_axis_offset(double t) {
    const SunMoon sm = sun_moon(t);
    return axis_offset(sm.moon, glm::normalize(sm.moon - sm.sun));
}

glm::dvec3 lunar_axis_offset(double t) {
    const SunMoon sm = sun_moon(t);
    return axis_offset(sm.moon, -glm::normalize(sm.sun));
}

// Steps from t0 through the minima of separation(t) (new or full moons) and returns the first
// event that at_syzygy(t_before, t_after) accepts; at_syzygy gets the bracket of one minimum.
template <class Sep, class AtSyzygy>
EclipseEvent scan(double t0, Sep separation, AtSyzygy at_syzygy, const char* what) {
    double ta = t0 - kScanStep_s, fa = separation(ta), tb = t0, fb = separation(tb);
    for (double tc = t0 + kScanStep_s; tc < t0 + kScanSpan_s; tc += kScanStep_s) {
        const double fc = separation(tc);
        if (fb < fa && fb <= fc) {
            const double ts = minimise(separation, ta, tc, 60.0);
            if (separation(ts) < kEclipseLimit_rad)
                if (std::optional<EclipseEvent> e = at_syzygy(ts); e && e->peak_tt_s > t0) return *e;
        }
        ta = tb, fa = fb, tb = tc, fb = fc;
    }
    throw std::runtime_error(std::string("no ") + what + " eclipse within two years after " + tt_to_utc_iso(t0));
}

}  // namespace

SolarEclipseAt solar_eclipse_at(double t_tt_s) {
    const SunMoon sm = sun_moon(t_tt_s);
    const glm::dmat3 r = gcrs_to_itrs(t_tt_s);
    const glm::dvec3 a = glm::normalize(sm.moon - sm.sun);
    const auto [q, hit] = axis_surface_point(r * sm.moon, r * a);
    const Local local = local_solar(sm, glm::transpose(r) * q);
    SolarEclipseAt e;
    e.type = local.type;
    e.magnitude = local.magnitude;
    e.central = hit;
    e.gamma = signed_gamma(axis_offset(sm.moon, a), r);
    double xyz[3] = {q.x, q.y, q.z}, elong, phi, height;
    eraGc2gd(ERFA_WGS84, xyz, &elong, &phi, &height);
    e.lat_deg = phi * ERFA_DR2D;
    e.lon_deg = elong * ERFA_DR2D;
    return e;
}

EclipseEvent next_solar_eclipse(double t_tt_s) {
    auto separation = [](double t) {
        const SunMoon sm = sun_moon(t);
        return angle_between(sm.sun, sm.moon);
    };
    auto at_new_moon = [](double t_new) -> std::optional<EclipseEvent> {
        EclipseEvent e;
        e.peak_tt_s = minimise([](double t) { return glm::length(solar_axis_offset(t)); }, t_new - kPeakWindow_s,
                               t_new + kPeakWindow_s, 0.05);
        const SolarEclipseAt at = solar_eclipse_at(e.peak_tt_s);
        if (at.type == "none") return std::nullopt;  // the penumbra misses the Earth
        // Central: total or annular where the axis meets the Earth. Otherwise partial (the rare
        // non-central total/annular eclipses, axis just missing, are reported as partial).
        e.type = at.central ? at.type : "partial";
        e.lat_deg = at.lat_deg, e.lon_deg = at.lon_deg, e.magnitude = at.magnitude, e.gamma = at.gamma;
        return e;
    };
    return scan(t_tt_s, separation, at_new_moon, "solar");
}

EclipseEvent next_lunar_eclipse(double t_tt_s) {
    auto separation = [](double t) {
        const SunMoon sm = sun_moon(t);
        return angle_between(-sm.sun, sm.moon);
    };
    auto at_full_moon = [](double t_full) -> std::optional<EclipseEvent> {
        EclipseEvent e;
        e.peak_tt_s = minimise([](double t) { return glm::length(lunar_axis_offset(t)); }, t_full - kPeakWindow_s,
                               t_full + kPeakWindow_s, 0.05);
        const SunMoon sm = sun_moon(e.peak_tt_s);
        const double ds = glm::length(sm.sun), dm = glm::length(sm.moon);
        const double pi_m = std::asin(kEarthEquatorialRadius_m / dm), pi_s = std::asin(kEarthEquatorialRadius_m / ds);
        const double s_s = std::asin(kSunRadius_m / ds), s_m = std::asin(kMoonRadius_m / dm);
        const double penumbra = 1.01 * pi_m + pi_s + s_s, umbra = 1.01 * pi_m + pi_s - s_s;  // Danjon
        const double sigma = angle_between(-sm.sun, sm.moon);
        const double umbral = (umbra + s_m - sigma) / (2.0 * s_m);
        e.penumbral_magnitude = (penumbra + s_m - sigma) / (2.0 * s_m);
        if (e.penumbral_magnitude <= 0.0) return std::nullopt;
        e.type = umbral >= 1.0 ? "total" : umbral > 0.0 ? "partial" : "penumbral";
        e.magnitude = umbral > 0.0 ? umbral : e.penumbral_magnitude;
        const glm::dmat3 r = gcrs_to_itrs(e.peak_tt_s);
        e.gamma = signed_gamma(axis_offset(sm.moon, -glm::normalize(sm.sun)), r);
        const glm::dvec3 q = r * sm.moon;  // sub-lunar point: the Moon's direction in ITRS
        e.lat_deg = std::atan2(q.z, std::hypot(q.x, q.y)) * ERFA_DR2D;
        e.lon_deg = std::atan2(q.y, q.x) * ERFA_DR2D;
        return e;
    };
    return scan(t_tt_s, separation, at_full_moon, "lunar");
}

}  // namespace cupola

#include "atmosphere/validation_set.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "atmosphere/atmosphere_geometry.hpp"

namespace cupola::atmosphere {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr double kLimbAltitude = 400000.0;
constexpr double kLimbBelowHorizonDeg = 2.0;

// Zenith cosine of the ray from radius r tangent to the sphere of radius `radius` < r, pointing
// down: -sqrt(1 - (radius/r)^2), formed as (r - radius)(r + radius) to avoid cancellation.
double mu_tangent(double r, double radius) { return -std::sqrt((r - radius) * (r + radius)) / r; }

// Appends n spherical-Fibonacci directions over the zenith-cosine band [mu_lo, mu_hi] (see the header).
void append_band(std::vector<ValidationCase>& out, const std::string& camera, double altitude, double sun_zenith_deg,
                 double mu_lo, double mu_hi, int n) {
    constexpr double kInvGolden = 1.0 / std::numbers::phi;  // frac(i / phi) = frac(i * (phi - 1))
    for (int i = 0; i < n; ++i) {
        const double mu = mu_hi - (mu_hi - mu_lo) * ((i + 0.5) / n);
        double az = 360.0 * std::fmod(i * kInvGolden, 1.0);
        if (az >= 180.0) az -= 360.0;
        ValidationCase c;
        c.camera = camera;
        c.query.altitude_m = altitude;
        c.query.view_zenith_deg = std::acos(mu) * kDeg;
        c.query.sun_zenith_deg = sun_zenith_deg;
        c.query.relative_azimuth_deg = az;
        out.push_back(std::move(c));
    }
}

}  // namespace

const std::vector<std::string>& validation_cameras() {
    static const std::vector<std::string> names = {"ground", "10km", "100km", "1000km", "limb"};
    return names;
}

const std::vector<double>& validation_sun_zeniths_deg() {
    static const std::vector<double> suns = {30.0, 65.0, 88.0, 95.0};
    return suns;
}

double validation_camera_altitude(const std::string& camera) {
    if (camera == "ground") return kMinCameraAltitude;
    if (camera == "10km") return 10000.0;
    if (camera == "100km") return 100000.0;
    if (camera == "1000km") return 1000000.0;
    if (camera == "limb") return kLimbAltitude;
    throw std::invalid_argument("unknown validation camera '" + camera + "'");
}

std::vector<ValidationCase> validation_set(const AtmosphereParameters& p, int directions_per_set) {
    if (directions_per_set < 1) throw std::invalid_argument("validation_set: directions_per_set must be >= 1");
    const double R = p.bottom_radius, top = p.top_radius;
    std::vector<ValidationCase> out;
    out.reserve(validation_cameras().size() * validation_sun_zeniths_deg().size() * directions_per_set);
    for (const std::string& camera : validation_cameras()) {
        const double altitude = validation_camera_altitude(camera);
        const double r = R + altitude;
        double mu_lo = -1.0, mu_hi = 1.0;  // inside the atmosphere: the full sphere
        if (camera == "limb") {
            if (r <= top) throw std::invalid_argument("validation_set: the limb camera is inside the atmosphere");
            const double horizon_zenith = std::acos(mu_tangent(r, R)) * kDeg;
            mu_lo = std::cos((horizon_zenith + kLimbBelowHorizonDeg) / kDeg);
            mu_hi = mu_tangent(r, top);
        } else if (r > top) {
            mu_hi = mu_tangent(r, top);  // the cap of rays that enter the atmosphere
        }
        for (double sun : validation_sun_zeniths_deg())
            append_band(out, camera, altitude, sun, mu_lo, mu_hi, directions_per_set);
    }
    return out;
}

}  // namespace cupola::atmosphere

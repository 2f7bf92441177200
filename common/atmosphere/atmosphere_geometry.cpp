#include "atmosphere/atmosphere_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace cupola::atmosphere {

double sphere_discriminant(double r, double mu, double radius) {
    const double m = std::clamp(mu, -1.0, 1.0);
    return radius * radius - r * r * ((1.0 - m) * (1.0 + m));
}

double distance_to_top(double r, double mu, double top) {
    const double m = std::clamp(mu, -1.0, 1.0);
    const double disc = sphere_discriminant(r, m, top);
    if (disc < 0.0) return 0.0;
    return std::max(0.0, -r * m + std::sqrt(disc));
}

double distance_to_ground(double r, double mu, double bottom) {
    const double m = std::clamp(mu, -1.0, 1.0);
    const double disc = sphere_discriminant(r, m, bottom);
    if (disc < 0.0) return 0.0;
    return std::max(0.0, -r * m - std::sqrt(disc));
}

double mu_horizon(double r, double bottom) {
    if (r <= bottom) return 0.0;
    // 1 - (R/r)^2 = (r - R)(r + R) / r^2, free of cancellation near the ground.
    return -std::sqrt((r - bottom) * (r + bottom)) / r;
}

bool ray_hits_ground(double r, double mu, double bottom) {
    if (r <= bottom) return std::clamp(mu, -1.0, 1.0) < 0.0;
    return mu < mu_horizon(r, bottom);
}

double distance_to_nearest_boundary(double r, double mu, double bottom, double top) {
    return ray_hits_ground(r, mu, bottom) ? distance_to_ground(r, mu, bottom) : distance_to_top(r, mu, top);
}

RayEntry enter_atmosphere(double r, double mu, double bottom, double top) {
    RayEntry e;
    const double m = std::clamp(mu, -1.0, 1.0);
    const double rc = std::max(r, bottom + kMinCameraAltitude);
    if (rc <= top) {
        e.intersects = true;
        e.r = rc;
        e.mu = m;
        return e;
    }
    const double disc = sphere_discriminant(rc, m, top);
    if (m >= 0.0 || disc < 0.0) return e;  // looking away or passing beside the atmosphere
    e.intersects = true;
    e.offset = std::max(0.0, -rc * m - std::sqrt(disc));
    e.r = top;
    // mu at the entry point: (r mu + d) / top (the radial component grows by d along the ray).
    e.mu = std::clamp((rc * m + e.offset) / top, -1.0, 1.0);
    return e;
}

}  // namespace cupola::atmosphere

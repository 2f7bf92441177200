#include "atmosphere/atmosphere_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace cupola::atmosphere {

RayEntry enter_atmosphere(double r_m, double mu, double bottom_m, double top_m) {
    RayEntry e;
    const double m = std::clamp(mu, -1.0, 1.0);
    const double rc = std::max(r_m, bottom_m + kMinCameraAltitude);
    if (rc <= top_m) {
        e.intersects = true;
        e.r_m = rc;
        e.mu = m;
        return e;
    }
    // Looking away or passing beside the atmosphere.
    if (m >= 0.0 || f64::ray_sphere_discriminant_m2(rc, m, top_m) < 0.0) return e;
    e.intersects = true;
    e.offset_m = f64::ray_sphere_near_m(rc, m, top_m);
    e.r_m = top_m;
    // mu at the entry point: (r mu + d) / top (the radial component grows by d along the ray).
    e.mu = std::clamp((rc * m + e.offset_m) / top_m, -1.0, 1.0);
    return e;
}

}  // namespace cupola::atmosphere

#include "passes/sphere_screen_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cupola {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// Image-plane bounds (tangent units, x/(-z)) of a circle (centre (a, z), radius r) in one plane
// through the eye: the two tangent lines from the eye. Unbounded when the eye is inside the
// circle or a tangent does not point ahead of the camera.
void plane_bounds(double a, double z, double r, double& lo, double& hi) {
    lo = -kInf;
    hi = kInf;
    const double rho2 = a * a + z * z;
    if (rho2 <= r * r) return;
    const double rho = std::sqrt(rho2), s = r / rho, c = std::sqrt((1.0 - s) * (1.0 + s));
    // The centre direction rotated by +-asin(r / rho) in the (a, z) plane.
    const double a1 = (a * c - z * s) / rho, z1 = (a * s + z * c) / rho;
    const double a2 = (a * c + z * s) / rho, z2 = (-a * s + z * c) / rho;
    if (z1 >= -1e-9 || z2 >= -1e-9) return;
    const double p1 = a1 / -z1, p2 = a2 / -z2;
    lo = std::min(p1, p2);
    hi = std::max(p1, p2);
}

// Pixel span [begin, end) of image-plane bounds over an axis from -tan_neg to tan_pos in n pixels.
void pixel_span(double lo, double hi, double tan_neg, double tan_pos, int n, int& begin, int& end) {
    const double scale = n / (tan_neg + tan_pos);
    const double b = std::floor((std::max(lo, -tan_neg) + tan_neg) * scale) - 1.0;
    const double e = std::ceil((std::min(hi, tan_pos) + tan_neg) * scale) + 1.0;
    begin = static_cast<int>(std::clamp(b, 0.0, static_cast<double>(n)));
    end = static_cast<int>(std::clamp(e, 0.0, static_cast<double>(n)));
}
}  // namespace

PixelRect sphere_screen_bounds(const ChannelFrustum& f, const glm::dvec3& c, double radius_m) {
    double x_lo, x_hi, y_lo, y_hi;
    plane_bounds(c.x, c.z, radius_m, x_lo, x_hi);
    plane_bounds(c.y, c.z, radius_m, y_lo, y_hi);
    PixelRect r;
    int x0, x1, y0, y1;
    pixel_span(x_lo, x_hi, f.tan_left(), f.tan_right(), f.width(), x0, x1);
    pixel_span(y_lo, y_hi, f.tan_down(), f.tan_up(), f.height(), y0, y1);
    r.x = x0;
    r.y = y0;
    r.width = x1 - x0;
    r.height = y1 - y0;
    return r;
}

}  // namespace cupola

#include "overlay/sky_arcs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cupola {

glm::dvec3 frame_dir(double lon_rad, double lat_rad) {
    return {std::cos(lat_rad) * std::cos(lon_rad), std::cos(lat_rad) * std::sin(lon_rad), std::sin(lat_rad)};
}

void add_great_circle(std::vector<SkyArc>& out, const glm::dvec3& a, const glm::dvec3& b, double max_step_rad) {
    const glm::dvec3 n = glm::cross(a, b);
    const double s = glm::length(n);
    if (!(s > 1e-12)) return;
    const glm::dvec3 pole = n / s;
    const double angle = std::atan2(s, glm::dot(a, b));
    const int pieces = std::max(1, static_cast<int>(std::ceil(angle / max_step_rad)));
    const glm::dvec3 t = glm::cross(pole, a);  // a rotated a quarter turn toward b
    glm::dvec3 prev = a;
    for (int i = 1; i <= pieces; ++i) {
        const double u = angle * i / pieces;
        const glm::dvec3 next = i == pieces ? b : std::cos(u) * a + std::sin(u) * t;
        out.push_back({prev, next, pole, 0.0});
        prev = next;
    }
}

void add_parallel(std::vector<SkyArc>& out, double lat_rad, double max_step_rad) {
    const double circumference = 2.0 * std::numbers::pi * std::cos(lat_rad);
    const int pieces = std::max(8, static_cast<int>(std::ceil(circumference / max_step_rad)));
    for (int i = 0; i < pieces; ++i) {
        const double l0 = 2.0 * std::numbers::pi * i / pieces, l1 = 2.0 * std::numbers::pi * (i + 1) / pieces;
        out.push_back({frame_dir(l0, lat_rad), frame_dir(l1, lat_rad), glm::dvec3(0.0, 0.0, 1.0), lat_rad});
    }
}

void add_meridian(std::vector<SkyArc>& out, double lon_rad, double lat_limit_rad, double max_step_rad) {
    const glm::dvec3 pole(-std::sin(lon_rad), std::cos(lon_rad), 0.0);  // east of the meridian's plane
    const int pieces = std::max(1, static_cast<int>(std::ceil(2.0 * lat_limit_rad / max_step_rad)));
    for (int i = 0; i < pieces; ++i) {
        const double b0 = -lat_limit_rad + 2.0 * lat_limit_rad * i / pieces;
        const double b1 = -lat_limit_rad + 2.0 * lat_limit_rad * (i + 1) / pieces;
        out.push_back({frame_dir(lon_rad, b0), frame_dir(lon_rad, b1), pole, 0.0});
    }
}

std::vector<SkyArc> coordinate_grid(double parallel_step_deg, double meridian_step_deg, bool with_equator,
                                    double max_step_rad) {
    std::vector<SkyArc> out;
    const int n = static_cast<int>(std::floor((90.0 - 1e-9) / parallel_step_deg));
    for (int k = -n; k <= n; ++k)
        if (k != 0 || with_equator) add_parallel(out, glm::radians(k * parallel_step_deg), max_step_rad);
    const double limit = glm::radians(n * parallel_step_deg);
    for (double lon = 0.0; lon < 360.0 - 1e-9; lon += meridian_step_deg)
        add_meridian(out, glm::radians(lon), limit, max_step_rad);
    return out;
}

}  // namespace cupola

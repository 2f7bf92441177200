#include "projection/fisheye.hpp"

#include <cmath>

namespace cupola {

// Dome frame basis: apex +Y, image right +X, image up +Z (towards the back of the dome).
std::optional<glm::dvec3> FisheyeMapping::uv_to_direction(const glm::dvec2& uv) const {
    const double r = std::sqrt(uv.x * uv.x + uv.y * uv.y);
    if (r > 1.0) return std::nullopt;
    const double theta = r * half_fov_rad_;
    const double phi = std::atan2(uv.y, uv.x);
    const double s = std::sin(theta);
    return glm::dvec3(s * std::cos(phi), std::cos(theta), s * std::sin(phi));
}

std::optional<glm::dvec2> FisheyeMapping::direction_to_uv(const glm::dvec3& d_in) const {
    const glm::dvec3 d = glm::normalize(d_in);
    const double theta = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y);
    if (theta > half_fov_rad_ + 1e-12) return std::nullopt;
    const double r = theta / half_fov_rad_;
    const double phi = std::atan2(d.z, d.x);
    return glm::dvec2(r * std::cos(phi), r * std::sin(phi));
}

glm::dvec2 FisheyeMapping::pixel_to_uv(const glm::dvec2& p, int size) {
    return glm::dvec2(p.x / size * 2.0 - 1.0, 1.0 - p.y / size * 2.0);
}

glm::dvec2 FisheyeMapping::uv_to_pixel(const glm::dvec2& uv, int size) {
    return glm::dvec2((uv.x + 1.0) * 0.5 * size, (1.0 - uv.y) * 0.5 * size);
}

}  // namespace cupola

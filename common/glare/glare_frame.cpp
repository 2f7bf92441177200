#include "glare/glare_frame.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cupola {

GlareFrame glare_frame(const glm::dvec3& center_world, const glm::dquat& camera_orientation) {
    GlareFrame f;
    f.center = glm::normalize(center_world);
    const glm::dmat3 cam = glm::mat3_cast(camera_orientation);
    glm::dvec3 up = cam[1];
    if (glm::length(glm::cross(f.center, up)) < 1e-6) up = -cam[2];
    f.right = glm::normalize(glm::cross(f.center, up));
    f.up = glm::cross(f.right, f.center);
    return f;
}

double glare_wedge_mid_angle(int wedge) { return (wedge + 0.5) * 2.0 * std::numbers::pi / GlareMeasurement::kWedges; }

glm::dvec3 glare_centroid_offset(const GlareFrame& frame, const float (&visible_sr)[GlareMeasurement::kWedges],
                                 double angular_radius) {
    const double h = std::numbers::pi / GlareMeasurement::kWedges;  // half a wedge
    const double wedge_centroid = 2.0 / 3.0 * angular_radius * std::sin(h) / h;
    double sum = 0.0, x = 0.0, y = 0.0;
    for (int i = 0; i < GlareMeasurement::kWedges; ++i) {
        const double a = glare_wedge_mid_angle(i);
        sum += visible_sr[i];
        x += visible_sr[i] * std::cos(a);
        y += visible_sr[i] * std::sin(a);
    }
    if (!(sum > 0.0)) return glm::dvec3(0.0);
    return wedge_centroid * (x / sum * frame.right + y / sum * frame.up);
}

bool disc_may_touch_frustum(const ChannelFrustum& frustum, const glm::dmat3& dome_from_world, const GlareFrame& frame,
                            double angular_radius) {
    if (frustum.contains(dome_from_world * frame.center)) return true;
    const double t = std::tan(std::min(angular_radius + 2e-3, 1.5));  // a little beyond the rim
    for (int i = 0; i < 16; ++i) {
        const double a = i * std::numbers::pi / 8.0;
        const glm::dvec3 rim = glm::normalize(frame.center + t * (std::cos(a) * frame.right + std::sin(a) * frame.up));
        if (frustum.contains(dome_from_world * rim)) return true;
    }
    return false;
}

}  // namespace cupola

#include "projection/channel_frustum.hpp"

#include <algorithm>
#include <cmath>

namespace cupola {

ChannelFrustum::ChannelFrustum(const EulerDeg& orientation, const FovDeg& fov, int width, int height)
    : orientation_(orientation), fov_(fov), width_(width), height_(height), rotation_(channel_rotation(orientation)) {
    tl_ = std::tan(glm::radians(fov.left_deg));
    tr_ = std::tan(glm::radians(fov.right_deg));
    tu_ = std::tan(glm::radians(fov.up_deg));
    td_ = std::tan(glm::radians(fov.down_deg));
}

glm::dmat4 ChannelFrustum::projection(double n, double f) const {
    const double l = -n * tl_, r = n * tr_, b = -n * td_, t = n * tu_;
    glm::dmat4 m(0.0);
    m[0][0] = 2.0 * n / (r - l);
    m[1][1] = 2.0 * n / (t - b);
    m[2][0] = (r + l) / (r - l);
    m[2][1] = (t + b) / (t - b);
    m[2][2] = -(f + n) / (f - n);
    m[2][3] = -1.0;
    m[3][2] = -2.0 * f * n / (f - n);
    return m;
}

std::optional<glm::dvec2> ChannelFrustum::dome_direction_to_pixel(const glm::dvec3& dome_dir) const {
    const glm::dvec3 c = glm::transpose(rotation_) * dome_dir;  // channel frame
    if (c.z >= -1e-12) return std::nullopt;
    const double tx = c.x / -c.z, ty = c.y / -c.z;
    const double fx = (tx + tl_) / (tl_ + tr_);  // 0 at left edge, 1 at right edge
    const double fy = (ty + td_) / (td_ + tu_);  // 0 at bottom edge, 1 at top edge
    return glm::dvec2(fx * width_, (1.0 - fy) * height_);
}

glm::dvec3 ChannelFrustum::pixel_to_dome_direction(const glm::dvec2& p) const {
    const double fx = p.x / width_, fy = 1.0 - p.y / height_;
    const glm::dvec3 c(-tl_ + fx * (tl_ + tr_), -td_ + fy * (td_ + tu_), -1.0);
    return glm::normalize(rotation_ * c);
}

bool ChannelFrustum::contains(const glm::dvec3& dome_dir) const {
    auto p = dome_direction_to_pixel(dome_dir);
    return p && p->x >= 0.0 && p->x <= width_ && p->y >= 0.0 && p->y <= height_;
}

double ChannelFrustum::edge_distance_px(const glm::dvec2& p) const {
    return std::min(std::min(p.x, width_ - p.x), std::min(p.y, height_ - p.y));
}

double ChannelFrustum::pixel_solid_angle(const glm::dvec2& p) const {
    // On the plane z = -1 a pixel covers dx*dy; the solid angle is dx*dy*cos^3 / 1 where cos is the
    // angle to the plane normal: dOmega = dA / (1 + x^2 + y^2)^{3/2}.
    const double dx = (tl_ + tr_) / width_, dy = (td_ + tu_) / height_;
    const double fx = p.x / width_, fy = 1.0 - p.y / height_;
    const double x = -tl_ + fx * (tl_ + tr_), y = -td_ + fy * (td_ + tu_);
    return dx * dy / std::pow(1.0 + x * x + y * y, 1.5);
}

}  // namespace cupola

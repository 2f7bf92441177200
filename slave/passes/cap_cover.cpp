#include "passes/cap_cover.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cupola {

namespace {
constexpr double kHalfStep_rad = std::numbers::pi / kCapCoverRim;  // half the azimuth between rim points
constexpr double kMaxRim_rad = 175.0 * std::numbers::pi / 180.0;

// Two unit vectors normal to the axis and to each other.
void normal_basis(const glm::dvec3& axis, glm::dvec3& e1, glm::dvec3& e2) {
    const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    e1 = glm::normalize(glm::cross(axis, helper));
    e2 = glm::cross(axis, e1);
}
}  // namespace

double cap_cover_inner_rad(double rim_rad) {
    // The edge's midpoint is the normalised mean of two rim directions at azimuths +-kHalfStep.
    const double mid = std::atan2(std::sin(rim_rad) * std::cos(kHalfStep_rad), std::cos(rim_rad));
    return std::min(mid, rim_rad);
}

CapCover cap_cover(const glm::dvec3& axis, double cone_rad, double margin_rad) {
    CapCover c;
    const double inner = std::max(cone_rad + margin_rad, 0.0);
    // Below 90 degrees the edges cut inside the rim: push the rim out until their midpoints reach
    // `inner` (tan(inner) = tan(rim) cos(half step)). Past 90 degrees the rim points are the nearest.
    c.rim_rad = std::max(inner, std::atan2(std::sin(inner), std::cos(inner) * std::cos(kHalfStep_rad)));
    if (!(c.rim_rad <= kMaxRim_rad)) return c;
    const glm::dvec3 a = glm::normalize(axis);
    glm::dvec3 e1, e2;
    normal_basis(a, e1, e2);
    c.directions[0] = a;
    const double s = std::sin(c.rim_rad), co = std::cos(c.rim_rad);
    for (int i = 0; i <= kCapCoverRim; ++i) {
        const double phi = 2.0 * kHalfStep_rad * (i % kCapCoverRim);
        c.directions[static_cast<size_t>(i) + 1] = co * a + s * (std::cos(phi) * e1 + std::sin(phi) * e2);
    }
    c.valid = true;
    return c;
}

}  // namespace cupola

#include "overlay/arc_chunks.hpp"

#include <algorithm>
#include <cmath>

namespace cupola {

namespace {
double angle_rad(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}
}  // namespace

std::vector<ArcChunk> arc_chunks(const std::vector<SkyArc>& arcs, int arcs_per_chunk) {
    std::vector<ArcChunk> out;
    for (int first = 0; first < static_cast<int>(arcs.size()); first += arcs_per_chunk) {
        ArcChunk c;
        c.first_arc = first;
        c.arc_count = std::min(arcs_per_chunk, static_cast<int>(arcs.size()) - first);
        glm::dvec3 sum(0.0);
        for (int i = first; i < first + c.arc_count; ++i) sum += arcs[i].a + arcs[i].b;
        // A run around a whole small circle sums to its pole's axis or to nothing: a hemisphere.
        c.centre = glm::length(sum) > 1e-9 ? glm::normalize(sum) : arcs[first].a;
        for (int i = first; i < first + c.arc_count; ++i)
            c.radius_rad = std::max({c.radius_rad, angle_rad(c.centre, arcs[i].a), angle_rad(c.centre, arcs[i].b)});
        out.push_back(c);
    }
    return out;
}

glm::dvec4 arc_cone(const SkyArc& arc) {
    const glm::dvec3 mid = arc.a + arc.b;
    const glm::dvec3 centre = glm::length(mid) > 1e-12 ? glm::normalize(mid) : arc.a;
    const double half_rad = 0.5 * angle_rad(arc.a, arc.b);
    // A small circle of latitude L curves by tan(L) (its geodesic curvature): its arc strays from
    // the great circle through its ends by about tan(L) half^2 / 2, under half^2 / cos(L) (taken
    // no smaller than at 89 degrees; the grids stop at 80).
    const double sag_rad = half_rad * half_rad / std::max(std::cos(arc.lat_rad), 0.017);
    return {centre, half_rad + sag_rad};
}

bool cone_touches_frustum(const glm::dvec3& centre, double radius_rad, const glm::dvec4& t) {
    return FrustumSides(t).touched_by(centre, radius_rad);
}

FrustumSides::FrustumSides(const glm::dvec4& t)
    : inward_{glm::normalize(glm::dvec3(1.0, 0.0, -t.x)), glm::normalize(glm::dvec3(-1.0, 0.0, -t.y)),
              glm::normalize(glm::dvec3(0.0, 1.0, -t.z)), glm::normalize(glm::dvec3(0.0, -1.0, -t.w))} {}

bool FrustumSides::touched_by(const glm::dvec3& centre, double radius_rad) const {
    if (radius_rad >= 1.5) return true;  // near a hemisphere or more: not worth testing
    const double reach = -std::sin(radius_rad);
    for (const glm::dvec3& n : inward_)
        if (glm::dot(centre, n) < reach) return false;
    return true;
}

}  // namespace cupola

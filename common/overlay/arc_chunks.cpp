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

bool cone_touches_frustum(const glm::dvec3& centre, double radius_rad, const glm::dvec4& t) {
    if (radius_rad >= 1.5) return true;  // near a hemisphere or more: not worth testing
    const glm::dvec3 planes[4] = {
        glm::normalize(glm::dvec3(1.0, 0.0, -t.x)), glm::normalize(glm::dvec3(-1.0, 0.0, -t.y)),
        glm::normalize(glm::dvec3(0.0, 1.0, -t.z)), glm::normalize(glm::dvec3(0.0, -1.0, -t.w))};
    const double reach = -std::sin(radius_rad);
    for (const glm::dvec3& n : planes)
        if (glm::dot(centre, n) < reach) return false;
    return true;
}

}  // namespace cupola

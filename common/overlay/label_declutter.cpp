#include "overlay/label_declutter.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cupola {

namespace {

// A label's tangent plane: right and up at its anchor, as the GPU stands the text
// (shaders/overlay_label.vert).
struct TangentPlane {
    glm::dvec3 anchor, right, up;
};

TangentPlane plane_at(const glm::dvec3& anchor, const glm::dvec3& up_world) {
    glm::dvec3 up = up_world - glm::dot(up_world, anchor) * anchor;
    if (glm::length(up) < 1e-4)
        up = std::abs(anchor.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) - anchor.y * anchor
                                      : glm::dvec3(1.0, 0.0, 0.0) - anchor.x * anchor;
    up = glm::normalize(up);
    return {anchor, glm::cross(anchor, up), up};
}

// The angle from the anchor to the box's farthest corner.
double reach_rad(const glm::dvec4& b) {
    return std::atan(
        std::max({std::hypot(b.x, b.y), std::hypot(b.z, b.y), std::hypot(b.x, b.w), std::hypot(b.z, b.w)}));
}

// Whether b's box, carried into a's tangent plane (gnomonic; the two planes nearly agree for labels
// close enough to touch), overlaps a's.
bool overlap(const TangentPlane& a, const LabelFootprint& la, const LabelFootprint& lb) {
    const double c = glm::dot(lb.anchor, a.anchor);
    if (c <= 0.0) return false;
    const double u = glm::dot(lb.anchor, a.right) / c, v = glm::dot(lb.anchor, a.up) / c;
    return u + lb.box.x < la.box.z && la.box.x < u + lb.box.z && v + lb.box.y < la.box.w && la.box.y < v + lb.box.w;
}

}  // namespace

std::vector<bool> declutter_labels(const std::vector<LabelFootprint>& labels, const glm::dvec3& up_world) {
    std::vector<size_t> order(labels.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return labels[a].priority < labels[b].priority; });
    std::vector<bool> kept(labels.size(), false);
    std::vector<size_t> placed;
    std::vector<TangentPlane> planes;
    for (const size_t i : order) {
        const LabelFootprint& l = labels[i];
        const double reach = reach_rad(l.box);
        bool clear = true;
        for (size_t k = 0; k < placed.size() && clear; ++k) {
            const LabelFootprint& other = labels[placed[k]];
            // Too far apart to touch: skip the projection.
            if (std::acos(std::clamp(glm::dot(l.anchor, other.anchor), -1.0, 1.0)) > reach + reach_rad(other.box))
                continue;
            clear = !overlap(planes[k], other, l);
        }
        if (!clear) continue;
        kept[i] = true;
        placed.push_back(i);
        planes.push_back(plane_at(l.anchor, up_world));
    }
    return kept;
}

}  // namespace cupola

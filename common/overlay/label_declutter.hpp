#pragma once
// Which of the presenter's labels are drawn, so that no two overlap: in order of priority, a label
// is kept unless its box overlaps the box of one already kept. The boxes are in angle on the sky
// (each label's size is in dome degrees), so the choice does not depend on any channel's
// projection: every node decides it from the same snapshot by this same rule, and a label that
// crosses the edge between two channels is kept or dropped in both.
#include <glm/glm.hpp>

#include <vector>

namespace cupola {

struct LabelFootprint {
    glm::dvec3 anchor{0.0, 0.0, 1.0};  // unit, world frame
    // The text's box in the tangent plane at the anchor, radians: x0, y0, x1, y1, x to the right
    // and y up (toward the labels' common up direction, as the GPU stands them).
    glm::dvec4 box{0.0};
    int priority = 0;  // lower first
};

// The labels' priorities (lower first): the cardinal points, the bodies, the named stars, the
// constellations' names.
enum LabelPriority : int { kCardinalPriority = 0, kBodyPriority = 1, kStarPriority = 2, kConstellationPriority = 3 };

// Whether each label is drawn. up_world: the direction the text stands up toward (the zenith, or
// the celestial pole). Equal priorities go in the labels' order.
std::vector<bool> declutter_labels(const std::vector<LabelFootprint>& labels, const glm::dvec3& up_world);

}  // namespace cupola

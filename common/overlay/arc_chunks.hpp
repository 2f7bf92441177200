#pragma once
// Runs of consecutive overlay arcs with the cone that bounds them, so that the overlay pass draws
// only the runs that can touch the channel: a whole-sky grid is mostly outside any one channel,
// and a CPU rasteriser pays for every vertex it is given.
#include <glm/glm.hpp>

#include <vector>

#include "overlay/sky_arcs.hpp"

namespace cupola {

struct ArcChunk {
    glm::dvec3 centre{0.0, 0.0, 1.0};  // unit, the overlay's frame
    double radius_rad = 0.0;           // every arc end within this angle of the centre
    int first_arc = 0, arc_count = 0;
};

// Chunks of at most arcs_per_chunk consecutive arcs.
std::vector<ArcChunk> arc_chunks(const std::vector<SkyArc>& arcs, int arcs_per_chunk);

// One arc's bounding cone: the unit direction halfway between its ends, and the angle (rad) within
// which all of it lies (half the angle between the ends plus the sag of a small circle's arc).
glm::dvec4 arc_cone(const SkyArc& arc);

// Whether a cone (unit centre in the channel frame: +X right, +Y up, -Z forward; half-angle
// radius_rad, below 90 degrees) can touch the frustum of tangents (left, right, down, up): false
// only when it lies wholly outside one of the four side planes.
bool cone_touches_frustum(const glm::dvec3& centre, double radius_rad, const glm::dvec4& tangents);

// The same test against one frustum for many cones: its four side planes' inward normals, once.
class FrustumSides {
public:
    explicit FrustumSides(const glm::dvec4& tangents);
    bool touched_by(const glm::dvec3& centre, double radius_rad) const;

private:
    glm::dvec3 inward_[4];
};

}  // namespace cupola

#pragma once
// The directions of a triangle fan whose projection covers a cone of directions: the cap of a
// sphere seen from the camera (or the corona around the Sun, or the top of an atmosphere), so a
// pass that shades a sphere runs on the pixels that can show it and not on a billboard's corners
// or the whole viewport. Pure geometry, double precision (channel frame, unit vectors).
#include <glm/glm.hpp>

#include <array>

namespace cupola {

constexpr int kCapCoverRim = 24;                     // rim directions of the fan
constexpr int kCapCoverVertices = kCapCoverRim + 2;  // the centre, the rim and the first rim point again

struct CapCover {
    // Vertex 0 is the cone's axis; 1..kCapCoverRim+1 run around the rim and close it. Each fan
    // triangle (axis, rim i, rim i+1) projects through the eye onto the spherical triangle of its
    // three directions, so the fan covers the spherical polygon of the rim.
    std::array<glm::dvec3, kCapCoverVertices> directions{};
    double rim_rad = 0.0;  // angle from the axis to each rim direction
    bool valid = false;    // false: the cone is (nearly) every direction; cover the viewport
};

// A fan whose spherical polygon contains every direction within cone_rad + margin_rad of the unit
// axis: the great-circle edges between rim directions come no closer to the axis than that.
// Valid up to a cone of 175 degrees.
CapCover cap_cover(const glm::dvec3& axis, double cone_rad, double margin_rad);

// The angle from the axis to the nearest point of the polygon's boundary: the edge midpoint's
// (the rim direction's, when the rim lies past 90 degrees and the edges bulge outward).
double cap_cover_inner_rad(double rim_rad);

}  // namespace cupola

#pragma once
// The cube-sphere: the six faces of a cube, each a square of (s, t) in [-1, 1]^2, projected onto
// the unit sphere (Sperlhofer 2011, section 4.4.2.1: a cube of six planar terrains whose vertices
// are normalized). The face coordinates are warped by tan(s pi/4) before the projection, so that a
// face's equal steps in s span nearly equal arcs (the plain projection makes the corner cells
// 5.2 times smaller in area than the centre cells; the warped, equiangular one 1.3 times; Ronchi,
// Iacono and Paolucci 1996, section 2).
//
// Body-fixed frame: +Z the north pole, +X the prime meridian on the equator, +Y longitude 90 E.
#include <glm/glm.hpp>

namespace cupola::terrain {

// The faces by their outward axis: +X, -X, +Y, -Y, +Z (north), -Z (south).
enum class CubeFace : int { PosX = 0, NegX = 1, PosY = 2, NegY = 3, PosZ = 4, NegZ = 5 };
constexpr int kCubeFaces = 6;

struct FacePoint {
    CubeFace face = CubeFace::PosX;
    double s = 0.0, t = 0.0;  // in [-1, 1]
};

// The face's outward normal and its right-handed in-face axes (s along u, t along v, u x v = n).
struct FaceAxes {
    glm::dvec3 n, u, v;
};
FaceAxes face_axes(CubeFace face);

// The unit direction of a face point, and the face point of a direction (the face its largest
// component names; ties go to the lower face index, so a point on a face's edge may come back on
// the neighbouring face). face_to_direction(direction_to_face(d)) is d to 1e-14
// (tests/test_terrain_tiles).
glm::dvec3 face_to_direction(const FacePoint& p);
FacePoint direction_to_face(const glm::dvec3& dir);

// Planetocentric latitude and longitude (radians, east positive, in (-pi, pi]) of a direction,
// and the unit direction of a latitude and longitude.
glm::dvec2 direction_to_lat_lon_rad(const glm::dvec3& dir);
glm::dvec3 lat_lon_to_direction(double lat_rad, double lon_rad);

}  // namespace cupola::terrain

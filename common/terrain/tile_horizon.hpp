#pragma once
// The relief's horizon at a tile's vertices, for its shadows: in each of eight compass directions
// the elevation of the highest relief seen from the vertex, as its sine (a horizon map, as Max
// 1988 introduced them for the shadows of bump-mapped surfaces).
// The GPU interpolates the horizon toward the Sun's azimuth and compares the Sun's elevation with
// it (shaders/shared/terrain_light.glsl, terrain_sun_visibility): a point whose horizon toward
// the Sun is higher than the Sun lies in a mountain's shadow.
//
// - Directions: azimuth k x 45 degrees counter-clockwise from east seen from above (east,
//   north-east, north, ...), in the local frame of shared/terrain_light.glsl (terrain_east).
// - Samples: along the great circle in each direction at s0, 1.5 s0, 1.5^2 s0, ... up to the
//   reach, s0 the tile's vertex spacing; each height from the relief band-limited to an eighth of
//   its distance (a far sample stands for a wider stretch). The Earth's curvature is exact: each
//   sample's elevation is taken from the vertex's own tangent plane.
// - The reach is what the highest relief casts at a Sun 1 degree high: the relief's range over
//   tan 1 degree, at most 5 % of the radius and at least 4 vertex spacings.
// - Cost: the horizon is computed at every stride-th vertex (stride = segments / 8: 9 x 9 points
//   for 32 segments) and interpolated bilinearly between, so shadows are resolved to a few
//   vertex spacings. The samples 16 tile widths away or more are taken once for the whole tile,
//   along the azimuths from its centre; each point measures its own elevation to them. Samples
//   that fall on the tile take the heights of its mesh (what is drawn there).
//   Deterministic from the tile's key: every node of a cluster computes the same.
#include <glm/glm.hpp>

#include <array>
#include <vector>

#include "terrain/relief.hpp"

namespace cupola::terrain {

struct TileMesh;

constexpr int kHorizonDirections = 8;
using HorizonSines = std::array<double, kHorizonDirections>;

// How far the horizon is searched (m along the ground).
double horizon_reach_m(const Relief& relief);

// The horizon seen from the point at unit direction d (body-fixed), height h0_m above the sphere,
// every sample its own (samples below reach_m).
HorizonSines horizon_sines(const Relief& relief, const glm::dvec3& d, double h0_m, double first_step_m, double reach_m);

// Eight sines in [-1, 1] as four floats, two 12-bit values in each (exact in a float's 24-bit
// significand): component c holds direction 2c in its high half and 2c + 1 in its low half.
// The GPU unpacks them with terrain_horizon_sine (shared/terrain_light.glsl).
glm::vec4 pack_horizon(const HorizonSines& sines);

// Every grid vertex's horizon (the order of TileMesh::directions), packed.
std::vector<glm::vec4> tile_horizon(const TileMesh& mesh, const Relief& relief);

}  // namespace cupola::terrain

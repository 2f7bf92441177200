#pragma once
// A tile's mesh, built on the CPU in double precision: (segments + 1)^2 vertices over the tile's
// face square, each at its relief height for the tile's sample spacing, plus a skirt, a ring of
// vertices hanging below each edge vertex, so that a neighbour of another level leaves no crack
// (Ulrich 2002, as Sperlhofer 2011, section 4.4.1.3, describes it). Each vertex also carries its
// geomorph target, the point of its parent tile's mesh at the same place: a vertex the parent
// has at the parent's height; one it lacks at the midpoint of the parent's edge or diagonal
// between its two neighbours, in 3-D (on the parent's flat triangle, not at the averaged height
// along the radius, which would lie h^2 / 2R above it). The GPU receives the positions relative
// to the tile's centre, as floats; the centre stays double on the CPU.
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "terrain/relief.hpp"
#include "terrain/tile_key.hpp"

namespace cupola::terrain {

struct TileMesh {
    TileKey key;
    int segments = 0;
    glm::dvec3 centre_m{0.0};             // body-fixed, double
    std::vector<glm::dvec3> directions;   // unit, (segments + 1)^2 row by row (v), then u
    std::vector<double> height_m;         // at this tile's spacing
    std::vector<double> parent_height_m;  // the parent mesh's height at the vertex
    // The surface's unit normal at each grid vertex (body-fixed): central differences of the
    // relief at this tile's spacing, across the tile's edges too (one sample beyond), so two
    // neighbours of a level agree along their shared edge.
    std::vector<glm::dvec3> normals;
    // The relief's horizon at each grid vertex, packed (terrain/tile_horizon.hpp); empty when the
    // mesh was built without it (the GPU then sees every vertex in the open).
    std::vector<glm::vec4> horizon;
    double skirt_depth_m = 0.0;   // how far the skirt hangs below the edge
    double bound_radius_m = 0.0;  // every vertex (either shape, the skirt too) lies within this of centre_m
    double radius_m = 0.0;        // the body's reference sphere
    int vertices_per_side() const { return segments + 1; }
    // The grid point (i along u, j along v).
    size_t index(int i, int j) const { return static_cast<size_t>(j) * (segments + 1) + i; }
    // Body-fixed position of a grid vertex at a morph factor (0: the parent's shape, 1: its own).
    glm::dvec3 position_m(int i, int j, double morph = 1.0) const;
    glm::dvec3 parent_position_m(int i, int j) const;
    // The mesh's height at (u, v) in [0, 1]^2 of the tile, interpolated in height over the
    // triangle that holds it (each quad split along its (i, j)-(i+1, j+1) diagonal). The GPU's
    // flat triangles lie below this by at most the chord's sag across the diagonal, h^2 / 4R,
    // which the cut's error counts.
    double height_on_mesh_m(double u, double v, double morph = 1.0) const;
    // Triangle indices (grid, then skirt) into the vertex list grid vertices then skirt vertices.
    std::vector<uint32_t> triangle_indices() const;
    // Every vertex as floats relative to centre_m, grid then skirt (the skirt's edge vertices
    // lowered by skirt_depth_m), with the morph target's offset alongside.
    struct GpuVertex {
        glm::vec3 position;      // own shape, relative to the centre
        glm::vec3 parent_delta;  // parent shape minus own shape
        glm::vec3 normal;        // unit, body-fixed (a skirt vertex takes its edge vertex's)
        glm::vec4 horizon;       // packed horizon (zeros without one; a skirt vertex takes its edge vertex's)
    };
    std::vector<GpuVertex> gpu_vertices() const;
};

// The mesh of a tile; segments must be even (the parent's vertices are every other one). With
// `horizon`, also its horizon map (the relief's shadows; several times the build's cost).
TileMesh build_tile_mesh(const TileKey& key, const Relief& relief, int segments, bool horizon = false);

}  // namespace cupola::terrain

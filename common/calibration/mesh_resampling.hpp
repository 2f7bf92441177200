#pragma once
// A mesh of nodes (a columns x rows lattice, each cell cut into two triangles, the way Bourke's
// mesh files and MPCDI's inverse maps are drawn) evaluated at the points of a regular target
// lattice: each target point inside a triangle gets the barycentric blend of the triangle's node
// values, exactly the piecewise-linear map the mesh describes. Used to put Paul Bourke meshes and
// inverse warp maps (content -> projector) onto projector_warp.hpp's fill-layout grid.
#include <vector>

#include <glm/glm.hpp>

namespace cupola {

struct NodeMesh {
    int columns = 0;
    int rows = 0;
    std::vector<glm::dvec2> position;  // columns * rows, row-major; a NaN position: node absent
    std::vector<glm::dvec3> value;     // columns * rows
};

// Target point (i, j) sits at origin + (i * step.x, j * step.y). Returns columns * rows values
// (row-major), NaN where no triangle of present nodes covers the point.
std::vector<glm::dvec3> resample_mesh(const NodeMesh& mesh, int columns, int rows, glm::dvec2 origin, glm::dvec2 step);

}  // namespace cupola

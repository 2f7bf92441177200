#include "terrain/tile_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "terrain/terrain_cut.hpp"
#include "terrain/tile_horizon.hpp"

namespace cupola::terrain {

namespace {

// The parent's vertices a grid point lies between: itself twice when the parent has it (both
// indices even); otherwise the two ends of the parent's edge, or of its quad's diagonal (the
// parent splits its quads along the same diagonal), it is the midpoint of.
struct ParentSpan {
    glm::ivec2 a, b;
};
ParentSpan parent_span(int i, int j) {
    const int di = i % 2, dj = j % 2;
    return {{i - di, j - dj}, {i + di, j + dj}};
}

// The parent's shape at the grid points: its vertices at its spacing, the points between them
// at the mean of the two.
void fill_parent_heights(TileMesh& m, const Relief& relief, double parent_spacing_m) {
    const int n = m.segments;
    m.parent_height_m.assign(m.height_m.size(), 0.0);
    for (int j = 0; j <= n; j += 2)
        for (int i = 0; i <= n; i += 2)
            m.parent_height_m[m.index(i, j)] = relief.height_m(m.directions[m.index(i, j)], parent_spacing_m);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const ParentSpan s = parent_span(i, j);
            m.parent_height_m[m.index(i, j)] =
                0.5 * (m.parent_height_m[m.index(s.a.x, s.a.y)] + m.parent_height_m[m.index(s.b.x, s.b.y)]);
        }
}

// The grid's edge vertices in order around the tile (for the skirt).
std::vector<size_t> edge_ring(const TileMesh& m) {
    const int n = m.segments;
    std::vector<size_t> ring;
    for (int i = 0; i < n; ++i) ring.push_back(m.index(i, 0));
    for (int j = 0; j < n; ++j) ring.push_back(m.index(n, j));
    for (int i = n; i > 0; --i) ring.push_back(m.index(i, n));
    for (int j = n; j > 0; --j) ring.push_back(m.index(0, j));
    return ring;
}

// The normals from a grid of heights one sample wider than the tile on every side.
void fill_normals(TileMesh& m, const Relief& relief, double spacing_m) {
    const int n = m.segments, w = n + 3;
    std::vector<glm::dvec3> p(static_cast<size_t>(w) * w);
    for (int j = -1; j <= n + 1; ++j)
        for (int i = -1; i <= n + 1; ++i) {
            const bool inside = i >= 0 && i <= n && j >= 0 && j <= n;
            const glm::dvec3 d = inside ? m.directions[m.index(i, j)]
                                        : m.key.direction(static_cast<double>(i) / n, static_cast<double>(j) / n);
            const double h = inside ? m.height_m[m.index(i, j)] : relief.height_m(d, spacing_m);
            p[static_cast<size_t>(j + 1) * w + (i + 1)] = d * (m.radius_m + h);
        }
    const auto at = [&](int i, int j) { return p[static_cast<size_t>(j + 1) * w + (i + 1)]; };
    m.normals.resize(m.directions.size());
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            glm::dvec3 nv = glm::cross(at(i + 1, j) - at(i - 1, j), at(i, j + 1) - at(i, j - 1));
            if (glm::dot(nv, m.directions[m.index(i, j)]) < 0.0) nv = -nv;
            m.normals[m.index(i, j)] = glm::normalize(nv);
        }
}

}  // namespace

glm::dvec3 TileMesh::parent_position_m(int i, int j) const {
    const auto vertex = [&](const glm::ivec2& g) {
        const size_t k = index(g.x, g.y);
        return directions[k] * (radius_m + parent_height_m[k]);
    };
    const ParentSpan s = parent_span(i, j);
    return 0.5 * (vertex(s.a) + vertex(s.b));
}

glm::dvec3 TileMesh::position_m(int i, int j, double morph) const {
    const glm::dvec3 own = directions[index(i, j)] * (radius_m + height_m[index(i, j)]);
    return glm::mix(parent_position_m(i, j), own, morph);
}

TileMesh build_tile_mesh(const TileKey& key, const Relief& relief, int segments, bool horizon) {
    if (segments < 2 || segments % 2 || segments > 256)
        throw std::invalid_argument("tile mesh: " + std::to_string(segments) + " segments (even, 2..256)");
    TileMesh m;
    m.key = key;
    m.segments = segments;
    m.radius_m = relief.radius_m();
    const double spacing = tile_spacing_m(key.level, segments, relief.radius_m());
    const int n = segments;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const glm::dvec3 d = key.direction(static_cast<double>(i) / n, static_cast<double>(j) / n);
            m.directions.push_back(d);
            m.height_m.push_back(relief.height_m(d, spacing));
        }
    fill_parent_heights(m, relief, key.level == 0 ? spacing : tile_spacing_m(key.level - 1, segments, m.radius_m));
    fill_normals(m, relief, spacing);
    m.centre_m = key.direction(0.5, 0.5) * m.radius_m;
    // Deep enough for the step a neighbour two levels coarser (a cut neighbour, or a stand-in)
    // can leave at the shared edge: both meshes' errors and the coarser chord's sag.
    const double coarse = 4.0 * spacing;
    m.skirt_depth_m =
        relief.mesh_error_m(spacing) + relief.mesh_error_m(coarse) + coarse * coarse / (4.0 * m.radius_m) + 1.0;
    // Every vertex, own or parent shape, skirt included, within the bound.
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.bound_radius_m = std::max({m.bound_radius_m, glm::length(m.position_m(i, j) - m.centre_m),
                                         glm::length(m.parent_position_m(i, j) - m.centre_m)});
    m.bound_radius_m += m.skirt_depth_m;
    if (horizon) m.horizon = tile_horizon(m, relief);
    return m;
}

double TileMesh::height_on_mesh_m(double u, double v, double morph) const {
    const double x = std::clamp(u, 0.0, 1.0) * segments, y = std::clamp(v, 0.0, 1.0) * segments;
    const int i = std::min(static_cast<int>(x), segments - 1), j = std::min(static_cast<int>(y), segments - 1);
    const double fx = x - i, fy = y - j;
    const auto h = [&](int a, int b) {
        const size_t k = index(a, b);
        return parent_height_m[k] + morph * (height_m[k] - parent_height_m[k]);
    };
    // Triangles (i,j)-(i+1,j)-(i+1,j+1) where fx >= fy, and (i,j)-(i+1,j+1)-(i,j+1) otherwise.
    if (fx >= fy) return h(i, j) + fx * (h(i + 1, j) - h(i, j)) + fy * (h(i + 1, j + 1) - h(i + 1, j));
    return h(i, j) + fy * (h(i, j + 1) - h(i, j)) + fx * (h(i + 1, j + 1) - h(i, j + 1));
}

std::vector<uint32_t> TileMesh::triangle_indices() const {
    const int n = segments;
    std::vector<uint32_t> idx;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const auto a = static_cast<uint32_t>(index(i, j)), b = static_cast<uint32_t>(index(i + 1, j)),
                       c = static_cast<uint32_t>(index(i + 1, j + 1)), d = static_cast<uint32_t>(index(i, j + 1));
            idx.insert(idx.end(), {a, b, c, a, c, d});
        }
    const std::vector<size_t> ring = edge_ring(*this);
    const auto grid_count = static_cast<uint32_t>(directions.size());
    for (size_t k = 0; k < ring.size(); ++k) {
        const size_t k1 = (k + 1) % ring.size();
        const auto top0 = static_cast<uint32_t>(ring[k]), top1 = static_cast<uint32_t>(ring[k1]);
        const auto low0 = grid_count + static_cast<uint32_t>(k), low1 = grid_count + static_cast<uint32_t>(k1);
        idx.insert(idx.end(), {top0, low0, low1, top0, low1, top1});
    }
    return idx;
}

std::vector<TileMesh::GpuVertex> TileMesh::gpu_vertices() const {
    std::vector<GpuVertex> out;
    const auto vertex = [&](size_t k, double drop_m) {
        const int i = static_cast<int>(k % static_cast<size_t>(segments + 1)),
                  j = static_cast<int>(k / static_cast<size_t>(segments + 1));
        const glm::dvec3 own = position_m(i, j) - directions[k] * drop_m;
        const glm::dvec3 parent = parent_position_m(i, j) - directions[k] * drop_m;
        out.push_back({glm::vec3(own - centre_m), glm::vec3(parent - own), glm::vec3(normals[k]),
                       horizon.empty() ? glm::vec4(0.0f) : horizon[k]});
    };
    for (size_t k = 0; k < directions.size(); ++k) vertex(k, 0.0);
    for (size_t k : edge_ring(*this)) vertex(k, skirt_depth_m);
    return out;
}

}  // namespace cupola::terrain

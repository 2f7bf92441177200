#include "calibration/mesh_resampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cupola {

namespace {

struct Triangle {
    glm::dvec2 p[3];
    glm::dvec3 v[3];
};

bool present(const glm::dvec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// The target indices [lo, hi] whose coordinate origin + k * step lies within [a, b].
void index_range(double a, double b, double origin, double step, int count, int& lo, int& hi) {
    double k0 = (a - origin) / step, k1 = (b - origin) / step;
    if (k0 > k1) std::swap(k0, k1);
    k0 = std::clamp(k0, -1.0, static_cast<double>(count));  // before the conversion to int
    k1 = std::clamp(k1, -1.0, static_cast<double>(count));
    lo = std::max(0, static_cast<int>(std::ceil(k0 - 1e-9)));
    hi = std::min(count - 1, static_cast<int>(std::floor(k1 + 1e-9)));
}

void scatter(const Triangle& t, int columns, int rows, glm::dvec2 origin, glm::dvec2 step,
             std::vector<glm::dvec3>& out) {
    const glm::dvec2 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
    const double det = e1.x * e2.y - e1.y * e2.x;
    if (std::abs(det) < 1e-300) return;
    int i0, i1, j0, j1;
    index_range(std::min({t.p[0].x, t.p[1].x, t.p[2].x}), std::max({t.p[0].x, t.p[1].x, t.p[2].x}), origin.x, step.x,
                columns, i0, i1);
    index_range(std::min({t.p[0].y, t.p[1].y, t.p[2].y}), std::max({t.p[0].y, t.p[1].y, t.p[2].y}), origin.y, step.y,
                rows, j0, j1);
    const double eps = 1e-9;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            const glm::dvec2 d = origin + glm::dvec2(i * step.x, j * step.y) - t.p[0];
            const double b1 = (d.x * e2.y - d.y * e2.x) / det, b2 = (e1.x * d.y - e1.y * d.x) / det;
            if (b1 < -eps || b2 < -eps || b1 + b2 > 1.0 + eps) continue;
            out[static_cast<size_t>(j) * columns + i] = t.v[0] * (1.0 - b1 - b2) + t.v[1] * b1 + t.v[2] * b2;
        }
}

}  // namespace

std::vector<glm::dvec3> resample_mesh(const NodeMesh& mesh, int columns, int rows, glm::dvec2 origin, glm::dvec2 step) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<glm::dvec3> out(static_cast<size_t>(columns) * rows, glm::dvec3(nan));
    auto node = [&](int i, int j) { return static_cast<size_t>(j) * mesh.columns + i; };
    for (int j = 0; j + 1 < mesh.rows; ++j)
        for (int i = 0; i + 1 < mesh.columns; ++i) {
            const size_t a = node(i, j), b = node(i + 1, j), c = node(i, j + 1), d = node(i + 1, j + 1);
            const size_t tris[2][3] = {{a, b, c}, {b, d, c}};
            for (const auto& tri : tris) {
                Triangle t;
                bool ok = true;
                for (int k = 0; k < 3; ++k) {
                    t.p[k] = mesh.position[tri[k]];
                    t.v[k] = mesh.value[tri[k]];
                    ok = ok && present(t.p[k]);
                }
                if (ok) scatter(t, columns, rows, origin, step, out);
            }
        }
    return out;
}

}  // namespace cupola

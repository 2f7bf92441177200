#include "terrain/tile_horizon.hpp"

#include <algorithm>
#include <cmath>

#include "shading/shared_shading.hpp"
#include "terrain/terrain_cut.hpp"
#include "terrain/tile_mesh.hpp"

namespace cupola::terrain {

namespace {

constexpr double kReachSunElevationRad = 0.017453292519943295;  // 1 degree
constexpr double kStepRatio = 1.5;

// The tangent direction of azimuth k at d: east, turned k x 45 degrees toward north.
glm::dvec3 azimuth_direction(const glm::dvec3& d, int k) {
    const glm::dvec3 east = glm::dvec3(shading::terrain_east(glm::vec3(d)));
    const glm::dvec3 e = glm::normalize(east - d * glm::dot(east, d));
    const glm::dvec3 north = glm::cross(d, e);
    const double a = k * (3.14159265358979323846 / 4.0);
    return std::cos(a) * e + std::sin(a) * north;
}

// The sine of the elevation of the relief at arc length s along t from the point (d, h0).
double sample_sine(const Relief& relief, const glm::dvec3& d, const glm::dvec3& t, double h0_m, double s_m) {
    const double r = relief.radius_m(), a = s_m / r;
    const glm::dvec3 q = d * std::cos(a) + t * std::sin(a);
    const double h = relief.height_m(q, s_m / 8.0);
    const glm::dvec3 p = q * (r + h) - d * (r + h0_m);
    const double len = glm::length(p);
    return len > 0.0 ? glm::dot(p, d) / len : -1.0;
}

}  // namespace

double horizon_reach_m(const Relief& relief) {
    const double range = relief.max_height_m() - relief.min_height_m();
    return std::min(range / std::tan(kReachSunElevationRad), 0.05 * relief.radius_m());
}

HorizonSines horizon_sines(const Relief& relief, const glm::dvec3& d, double h0_m, double first_step_m,
                           double reach_m) {
    HorizonSines out;
    for (int k = 0; k < kHorizonDirections; ++k) {
        const glm::dvec3 t = azimuth_direction(d, k);
        double best = -1.0;
        for (double s = first_step_m; s <= reach_m; s *= kStepRatio)
            best = std::max(best, sample_sine(relief, d, t, h0_m, s));
        out[k] = best;
    }
    return out;
}

glm::vec4 pack_horizon(const HorizonSines& sines) {
    const auto q = [&](int k) { return std::round((std::clamp(sines[k], -1.0, 1.0) + 1.0) * 0.5 * 4095.0); };
    glm::vec4 out;
    for (int c = 0; c < 4; ++c) out[c] = static_cast<float>(q(2 * c) * 4096.0 + q(2 * c + 1));
    return out;
}

std::vector<glm::vec4> tile_horizon(const TileMesh& mesh, const Relief& relief) {
    const int n = mesh.segments, stride = std::max(1, n / 8), m = n / stride;
    const double spacing = tile_spacing_m(mesh.key.level, n, mesh.radius_m);
    const double reach = std::max(horizon_reach_m(relief), 4.0 * spacing);
    // The horizon at the coarse points (every stride-th vertex).
    std::vector<HorizonSines> coarse(static_cast<size_t>(m + 1) * (m + 1));
    for (int b = 0; b <= m; ++b)
        for (int a = 0; a <= m; ++a) {
            const size_t k = mesh.index(a * stride, b * stride);
            coarse[static_cast<size_t>(b) * (m + 1) + a] =
                horizon_sines(relief, mesh.directions[k], mesh.height_m[k], spacing, reach);
        }
    // Bilinear between them at every vertex.
    std::vector<glm::vec4> out(mesh.directions.size());
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const int a = std::min(i / stride, m - 1), b = std::min(j / stride, m - 1);
            const double fx = static_cast<double>(i - a * stride) / stride,
                         fy = static_cast<double>(j - b * stride) / stride;
            const auto at = [&](int x, int y) -> const HorizonSines& {
                return coarse[static_cast<size_t>(y) * (m + 1) + x];
            };
            HorizonSines s;
            for (int k = 0; k < kHorizonDirections; ++k)
                s[k] = (1 - fy) * ((1 - fx) * at(a, b)[k] + fx * at(a + 1, b)[k]) +
                       fy * ((1 - fx) * at(a, b + 1)[k] + fx * at(a + 1, b + 1)[k]);
            out[mesh.index(i, j)] = pack_horizon(s);
        }
    return out;
}

}  // namespace cupola::terrain

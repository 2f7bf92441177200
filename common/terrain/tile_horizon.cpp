#include "terrain/tile_horizon.hpp"

#include <algorithm>
#include <cmath>

#include "shading/shared_shading.hpp"
#include "terrain/cube_sphere.hpp"
#include "terrain/terrain_cut.hpp"
#include "terrain/tile_mesh.hpp"

namespace cupola::terrain {

namespace {

constexpr double kReachSunElevationRad = 0.017453292519943295;  // 1 degree
constexpr double kStepRatio = 1.5;
// Samples this many tile widths away or more are shared by the whole tile (see tile_horizon).
constexpr double kSharedFarTiles = 16.0;

// The tangent directions of the eight azimuths at d: east, turned k x 45 degrees toward north.
std::array<glm::dvec3, kHorizonDirections> azimuth_directions(const glm::dvec3& d) {
    const glm::dvec3 east = glm::dvec3(shading::terrain_east(glm::vec3(d)));
    const glm::dvec3 e = glm::normalize(east - d * glm::dot(east, d));
    const glm::dvec3 north = glm::cross(d, e);
    std::array<glm::dvec3, kHorizonDirections> out;
    for (int k = 0; k < kHorizonDirections; ++k) {
        const double a = k * (3.14159265358979323846 / 4.0);
        out[k] = std::cos(a) * e + std::sin(a) * north;
    }
    return out;
}

// The relief's height under a sample: on the tile's own mesh where the sample lies on the tile
// (what is drawn there: its vertices' heights, interpolated), else the relief band-limited to the
// sample's band.
class SampleHeights {
public:
    SampleHeights(const Relief& relief, const TileMesh* mesh) : relief_(relief), mesh_(mesh) {
        if (mesh) st0_ = mesh->key.face_st(0.0, 0.0), st1_ = mesh->key.face_st(1.0, 1.0);
    }
    double height_m(const glm::dvec3& q, double band_m) const {
        if (mesh_) {
            const FacePoint f = direction_to_face(q);
            const double u = (f.s - st0_.x) / (st1_.x - st0_.x), v = (f.t - st0_.y) / (st1_.y - st0_.y);
            if (f.face == mesh_->key.face && u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0)
                return mesh_->height_on_mesh_m(u, v);
        }
        return relief_.height_m(q, band_m);
    }
    const Relief& relief() const { return relief_; }

private:
    const Relief& relief_;
    const TileMesh* mesh_;
    glm::dvec2 st0_{0.0}, st1_{1.0};
};

// The relief's point (body-fixed, m) at arc length s along t from d, band-limited to s / 8.
glm::dvec3 relief_point_m(const SampleHeights& heights, const glm::dvec3& d, const glm::dvec3& t, double s_m) {
    const double r = heights.relief().radius_m(), a = s_m / r;
    const glm::dvec3 q = d * std::cos(a) + t * std::sin(a);
    return q * (r + heights.height_m(q, s_m / 8.0));
}

// The sine of the elevation of point p seen from `from` (at unit direction d, its up).
double elevation_sine(const glm::dvec3& from, const glm::dvec3& d, const glm::dvec3& p) {
    const glm::dvec3 v = p - from;
    const double len = glm::length(v);
    return len > 0.0 ? glm::dot(v, d) / len : -1.0;
}

// The horizon from (d, h0) over the samples s_first, s_first x 1.5, ... below s_end.
HorizonSines near_horizon(const SampleHeights& heights, const glm::dvec3& d, double h0_m, double s_first_m,
                          double s_end_m) {
    const glm::dvec3 from = d * (heights.relief().radius_m() + h0_m);
    const auto toward = azimuth_directions(d);
    HorizonSines out;
    for (int k = 0; k < kHorizonDirections; ++k) {
        double best = -1.0;
        for (double s = s_first_m; s < s_end_m; s *= kStepRatio)
            best = std::max(best, elevation_sine(from, d, relief_point_m(heights, d, toward[k], s)));
        out[k] = best;
    }
    return out;
}

// A tile's far samples: in each azimuth from the tile's centre, the relief's points from s_far on.
struct FarSamples {
    std::array<std::vector<glm::dvec3>, kHorizonDirections> points_m;
};

FarSamples far_samples(const SampleHeights& heights, const glm::dvec3& centre, double s_far_m, double reach_m) {
    FarSamples out;
    const auto toward = azimuth_directions(centre);
    for (int k = 0; k < kHorizonDirections; ++k)
        for (double s = s_far_m; s <= reach_m; s *= kStepRatio)
            out.points_m[k].push_back(relief_point_m(heights, centre, toward[k], s));
    return out;
}

// The horizon of a tile's point: its own near samples, then the tile's shared far ones.
HorizonSines point_horizon(const SampleHeights& heights, const glm::dvec3& d, double h0_m, double first_step_m,
                           double s_far_m, const FarSamples& far) {
    HorizonSines out = near_horizon(heights, d, h0_m, first_step_m, s_far_m);
    const glm::dvec3 from = d * (heights.relief().radius_m() + h0_m);
    for (int k = 0; k < kHorizonDirections; ++k)
        for (const glm::dvec3& p : far.points_m[k]) out[k] = std::max(out[k], elevation_sine(from, d, p));
    return out;
}

}  // namespace

double horizon_reach_m(const Relief& relief) {
    const double range = relief.max_height_m() - relief.min_height_m();
    return std::min(range / std::tan(kReachSunElevationRad), 0.05 * relief.radius_m());
}

HorizonSines horizon_sines(const Relief& relief, const glm::dvec3& d, double h0_m, double first_step_m,
                           double reach_m) {
    return near_horizon(SampleHeights(relief, nullptr), d, h0_m, first_step_m, reach_m);
}

glm::vec4 pack_horizon(const HorizonSines& sines) {
    const auto q = [&](int k) { return std::round((std::clamp(sines[k], -1.0, 1.0) + 1.0) * 0.5 * 4095.0); };
    glm::vec4 out;
    for (int c = 0; c < 4; ++c) out[c] = static_cast<float>(q(2 * c) * 4096.0 + q(2 * c + 1));
    return out;
}

// The samples of the geometric progression s0, 1.5 s0, ... that lie kSharedFarTiles tile widths
// away or more are taken once for the whole tile, along each azimuth from its centre, and every
// point measures its elevation to those same relief points from its own position: a point lies
// at most 0.7 tile widths from the centre, so such a sample is off its own azimuth by at most
// 0.7 / 16 rad (2.5 degrees), well within the band (an eighth of its distance) that it stands for.
// The nearer samples that fall on the tile take its mesh's heights (SampleHeights).
std::vector<glm::vec4> tile_horizon(const TileMesh& mesh, const Relief& relief) {
    const int n = mesh.segments, stride = std::max(1, n / 8), m = n / stride;
    const double spacing = tile_spacing_m(mesh.key.level, n, mesh.radius_m);
    const double reach = std::max(horizon_reach_m(relief), 4.0 * spacing);
    double s_far = spacing;  // the progression's first sample at or past the shared distance
    while (s_far < kSharedFarTiles * n * spacing) s_far *= kStepRatio;
    const SampleHeights heights(relief, &mesh);
    const FarSamples far = far_samples(heights, mesh.key.direction(0.5, 0.5), s_far, reach);
    // The horizon at the coarse points (every stride-th vertex).
    std::vector<HorizonSines> coarse(static_cast<size_t>(m + 1) * (m + 1));
    for (int b = 0; b <= m; ++b)
        for (int a = 0; a <= m; ++a) {
            const size_t k = mesh.index(a * stride, b * stride);
            coarse[static_cast<size_t>(b) * (m + 1) + a] =
                point_horizon(heights, mesh.directions[k], mesh.height_m[k], spacing, s_far, far);
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

#include "terrain/procedural_relief.hpp"

#include <algorithm>
#include <cmath>

namespace cupola::terrain {

namespace {

uint64_t mix(uint64_t z) {  // splitmix64's finaliser (Steele, Lea and Flood 2014)
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// The gradient of the lattice point whose hash is h, dotted with the offset f from it.
double gradient_dot(uint64_t h, const glm::dvec3& f) {
    static constexpr double g[12][3] = {{1, 1, 0},  {-1, 1, 0},  {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                                        {1, 0, -1}, {-1, 0, -1}, {0, 1, 1},  {0, -1, 1},  {0, 1, -1}, {0, -1, -1}};
    const double* v = g[h % 12];
    return v[0] * f.x + v[1] * f.y + v[2] * f.z;
}

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// The weight of an octave of wavelength lambda in a mesh of spacing h: 1 down to 8h, 0 at 4h.
double octave_weight(double lambda, double h) {
    if (h <= 0.0 || lambda >= 8.0 * h) return 1.0;  // (log2 of 2 or more: the same 1)
    return std::clamp(std::log2(lambda / (4.0 * h)), 0.0, 1.0);
}

}  // namespace

double gradient_noise(const glm::dvec3& p, uint64_t seed) {
    const glm::dvec3 cell = glm::floor(p);
    const glm::dvec3 f = p - cell;
    const auto ix = static_cast<int64_t>(cell.x), iy = static_cast<int64_t>(cell.y), iz = static_cast<int64_t>(cell.z);
    const glm::dvec3 w(fade(f.x), fade(f.y), fade(f.z));
    // A lattice point's hash is mix(mix(mix(seed ^ x) ^ y) ^ z): the x and (x, y) stages are
    // shared by the corners that have them in common (14 mixes for the 8 corners, not 24).
    uint64_t hx[2], hxy[2][2];
    for (int dx = 0; dx < 2; ++dx) {
        hx[dx] = mix(seed ^ static_cast<uint64_t>(ix + dx));
        for (int dy = 0; dy < 2; ++dy) hxy[dx][dy] = mix(hx[dx] ^ static_cast<uint64_t>(iy + dy));
    }
    double x_lerp[2][2];
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy) {
            const uint64_t z = static_cast<uint64_t>(iz + dz);
            const double a = gradient_dot(mix(hxy[0][dy] ^ z), f - glm::dvec3(0, dy, dz));
            const double b = gradient_dot(mix(hxy[1][dy] ^ z), f - glm::dvec3(1, dy, dz));
            x_lerp[dz][dy] = a + w.x * (b - a);
        }
    const double y0 = x_lerp[0][0] + w.y * (x_lerp[0][1] - x_lerp[0][0]);
    const double y1 = x_lerp[1][0] + w.y * (x_lerp[1][1] - x_lerp[1][0]);
    return std::clamp(y0 + w.z * (y1 - y0), -1.0, 1.0);
}

double ProceduralRelief::height_m(const glm::dvec3& p_m, double spacing_m, double coarsest_wavelength_m) const {
    double h = 0.0, lambda = base_wavelength_m, a = base_amplitude_m;
    for (int k = 0; k < octaves; ++k, lambda *= 0.5, a *= gain) {
        if (coarsest_wavelength_m > 0.0 && lambda >= coarsest_wavelength_m) continue;
        const double w = octave_weight(lambda, spacing_m);
        if (w <= 0.0) break;
        h += w * a * gradient_noise(p_m / lambda, seed + static_cast<uint64_t>(k));
    }
    return h;
}

double ProceduralRelief::amplitude_bound_m() const {
    double s = 0.0, a = base_amplitude_m;
    for (int k = 0; k < octaves; ++k, a *= gain) s += a;
    return s;
}

// Left out or faded (lambda < 8h): the whole amplitude. Carried: a quintic-faded gradient noise
// of unit lattice has a second derivative below 16 per unit squared in any direction (largest
// measured: tests/test_terrain_relief), and linear interpolation over a mesh triangle whose
// longest side is the quad's diagonal sqrt(2) h misses at most (sqrt(2) h)^2 / 8 times that:
// 4 a (h / lambda)^2.
double ProceduralRelief::mesh_error_m(double spacing_m, double coarsest_wavelength_m) const {
    double e = 0.0, lambda = base_wavelength_m, a = base_amplitude_m;
    for (int k = 0; k < octaves; ++k, lambda *= 0.5, a *= gain) {
        if (coarsest_wavelength_m > 0.0 && lambda >= coarsest_wavelength_m) continue;
        e += lambda < 8.0 * spacing_m ? a : 4.0 * a * (spacing_m / lambda) * (spacing_m / lambda);
    }
    return e;
}

}  // namespace cupola::terrain

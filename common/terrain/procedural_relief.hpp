#pragma once
// Procedural relief: band-limited fractal gradient noise on the sphere, deterministic from the
// position (the same height on every node, frame and run). Octave k has wavelength
// base_wavelength_m / 2^k and amplitude base_amplitude_m * gain^k (gain = 2^-H for a surface of
// Hurst exponent H; Musgrave's fBm, Ebert et al. 2003, chapter 16). The octaves a mesh of a given
// sample spacing h cannot carry are left out: an octave is whole down to a wavelength of 8h and
// fades out linearly in log2 to nothing at 4h, so a finer tile adds detail without aliasing.
#include <glm/glm.hpp>

#include <cstdint>

namespace cupola::terrain {

struct ProceduralRelief {
    double base_wavelength_m = 200e3;
    double base_amplitude_m = 1500.0;
    double gain = 0.5;
    int octaves = 20;
    uint64_t seed = 1;

    // The height (m) at a point (body-fixed, metres; its direction is what matters at the scale
    // of the body) for a mesh of sample spacing spacing_m, with the octaves of wavelength at least
    // above_wavelength_m left out (the part a data set already carries; 0: none left out).
    double height_m(const glm::dvec3& p_m, double spacing_m, double coarsest_wavelength_m = 0.0) const;
    // Every octave's amplitude summed: the relief lies within +- this.
    double amplitude_bound_m() const;
    // A bound on the height error of a mesh of spacing h against the finest mesh: the octaves it
    // leaves out or fades, and the linear interpolation of those it carries.
    double mesh_error_m(double spacing_m, double coarsest_wavelength_m = 0.0) const;
};

// Gradient noise in [-1, 1] (Perlin 2002: quintic fade, gradients to the twelve cube edges),
// double precision, lattice hashed from integer coordinates and a seed.
double gradient_noise(const glm::dvec3& p, uint64_t seed);

}  // namespace cupola::terrain

#pragma once
// Double-precision reference for eclipse shadows, and the lookup table of the shader's LUT mode.
// Every eclipse mode of shaders/shared/eclipse_shadow.glsl is measured against it
// (tests/test_eclipse_shadow.cpp, benchmarks/eclipse_speed_vs_error.cpp).
//
// TERMS (as in eclipse_shadow.glsl). The Sun's apparent disc has radius 1; a = occluder radius /
// Sun radius, s = centre separation / Sun radius (both angular); the Sun's radiance follows the
// linear limb-darkening law I(r) = 1 - u (1 - sqrt(1 - r^2)), total flux pi (1 - u / 3).
//
// METHOD (deliberately unlike the shader's rings about the Sun's centre). The overlap of the two
// discs is cut into strips perpendicular to the line of centres (x along it, the Sun at x = 0, the
// occluder at x = s). At each x the strip is the chord |y| <= Y(x), Y = min(Sun chord, occluder
// chord); the switch happens at the radical line x0 = (1 - a^2 + s^2) / (2 s), so the chord is
// the occluder's on one side and the Sun's on the other. The integral of I along the chord is
// closed form: with h^2 = 1 - x^2,
//   int_{-Y}^{Y} I dy = 2 Y (1 - u) + u [Y sqrt(h^2 - Y^2) + h^2 atan2(Y, sqrt(h^2 - Y^2))],
// where h^2 - Y^2 = 2 s (x0 - x) exactly on the occluder side (no cancellation). The outer
// integral over x runs over the two pieces [max(-1, s - a), x0] and [x0, min(1, s + a)] with
// globally adaptive 21-point Gauss-Kronrod (QUADPACK QAG style: always bisect the interval with
// the largest |K21 - G10|) to an absolute tolerance of 1e-14 on the occluded flux. Each piece has
// square-root ends (chords vanish there); bisection resolves them.
//
// ACCURACY. The integrator's own bound (sum of |K21 - G10|) is below 5e-15 of the visible
// fraction; tests/test_eclipse_shadow.cpp measures, for a from 2^-12 to 2^12 with s over every
// regime (partial, total, annular, a > 1, s -> 0, tangent discs): |reference - circle-
// intersection area| for u = 0 <= 3e-13 (that closed form's own rounding at a ~ 2400; 2e-14
// elsewhere), the concentric closed form within 1e-13, the small-occluder limit (with its a^2
// Laplacian term) within 1e-6 relative, and a second integration (rings about the Sun's centre:
// other coordinates, other quadrature) within 1.3e-15. So ~1e-13 absolute, far inside the ~1e-10
// asked of it. Cost: 10-40 us per call (1-2.5 thousand integrand evaluations), up to ~0.1 ms
// for huge occluders; a rounding-noise guard stops at 4000 intervals (~20 ms).
#include <cstdint>

#include "shading/glsl_compat.hpp"

namespace cupola::eclipse {

// Visible fraction of the limb-darkened Sun's flux behind an occluder disc, in [0, 1].
// a > 0 (finite), s >= 0 (a negative s counts as |s|), u in [0, 1]. Throws std::invalid_argument
// for a <= 0, non-finite a or s, or u outside [0, 1].
double visible_fraction_reference(double a, double s, double u);

// The same, with the error bound reached by the integrator (the sum of |K21 - G10| over the final
// intervals, relative to the total flux) and the number of integrand evaluations.
struct ReferenceResult {
    double visible = 1.0;
    double error_bound = 0.0;
    int64_t evaluations = 0;
};
ReferenceResult visible_fraction_reference_detail(double a, double s, double u);

// The LUT of ECLIPSE_MODE_LUT for limb-darkening coefficient u: texel (i, j) holds
// visible_fraction_reference(a, s, u) at (a, s) = eclipse_lut_parameters(vec2(i / (width - 1),
// j / (height - 1))), the shader's inverse of eclipse_lut_coordinates (its comment has the
// layout: columns in log2 a packed around a = 1, rows from s = 0 through the inner contact to
// first contact), i.e. exactly the point whose texel centre the shader samples. r = g = b = the
// visible fraction, alpha = 1; row j = 0 first (texture coordinate v = 0), as Texture2DData and
// GlTexture expect. width, height >= 2 (for the exact contact row and a = 1 column, width odd and
// (height - 1) / 8 an integer); u in [0, 1]. Computing it takes all hardware threads (65 x 65:
// ~55 ms on 2 cores, a tenth of a slave's start-up), so it is kept on disk
// (load_or_compute_eclipse_lut), and later calls with the same (u, width, height) in a process
// return the memoised table.
shading::Texture2DData build_eclipse_lut(double u, int width, int height);

// The table from the cache on disk (image/table_file.hpp: $CUPOLA_CACHE_DIR, else
// ~/.cache/cupola/eclipse), or computed and stored there; a damaged file is logged and replaced.
// The key is the table's inputs and the code that computes it. Not memoised.
shading::Texture2DData load_or_compute_eclipse_lut(double u, int width, int height);

// Computed, without the cache or the memo.
shading::Texture2DData compute_eclipse_lut(double u, int width, int height);

// Default table size, from the measured error/cost trade-off (docs/eclipse-speed-vs-error.md).
inline constexpr int kEclipseLutWidth = 65;
inline constexpr int kEclipseLutHeight = 65;

}  // namespace cupola::eclipse

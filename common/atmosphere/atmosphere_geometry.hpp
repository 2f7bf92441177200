#pragma once
// Ray-sphere geometry of a spherical atmosphere in double precision, for the reference integrator:
// the routines of shaders/shared/ray_sphere.glsl (the ones the GPU and the production model run
// in float) included here with real = double as namespace f64, in the (r, mu) parametrisation:
// r_m is the distance of the ray origin from the planet centre, mu the cosine of the ray's zenith
// angle there. f64::ray_sphere_discriminant_m2, f64::ray_sphere_far_m, f64::ray_sphere_near_m,
// f64::ray_hits_sphere, f64::ray_sphere_horizon_mu, f64::ray_shell_exit_m.
#include <algorithm>
#include <cmath>

namespace cupola::atmosphere {

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
namespace f64 {
namespace {  // GLSL has no `inline`: internal linkage, as in shading/shared_shading.hpp
using real = double;
using std::max;
using std::sqrt;
#include "shared/ray_sphere.glsl"
}  // namespace
}  // namespace f64
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

// The smallest camera altitude the integrator accepts (m); cameras below are raised to it
// (a camera exactly at or inside the ground would otherwise give empty or negative paths).
inline constexpr double kMinCameraAltitude = 1.0;

// Result of bringing a camera that may be outside the atmosphere to the start of its ray's
// atmospheric part.
struct RayEntry {
    bool intersects = false;  // false: the ray never enters the atmosphere
    double offset_m = 0.0;    // distance from the camera to the start (0 for a camera inside)
    double r_m = 0.0;         // start radius (== top for a camera outside)
    double mu = 0.0;          // cosine of the zenith angle at the start
};
// r_m is first clamped to bottom_m + kMinCameraAltitude. For r_m > top_m the origin is moved
// explicitly to the entry point on the top sphere (no reliance on NaN from a negative square root).
RayEntry enter_atmosphere(double r_m, double mu, double bottom_m, double top_m);

}  // namespace cupola::atmosphere

// Ray-sphere geometry in the (r, mu) parametrisation (shared by GLSL and C++, in both precisions):
// r_m = distance of the ray origin from the sphere's centre, mu = cosine of the ray's zenith angle
// there (the angle from the outward radial direction). The scalar type `real` is float on the GPU
// (the #define below, GLSL only) and in shading:: (glsl_compat.hpp); the reference integrator
// includes this file with real = double (common/atmosphere/atmosphere_geometry.hpp). Keep to
// scalars, so that both instantiations are the same code.
//
// Discriminants are formed as (R - r)(R + r) + (r mu)^2: in float, R^2 - r^2 would lose the
// altitude of a camera near the ground (R^2 ~ 4e13 has an ulp of 4e6 m^2), and the ground/sky
// decision at the horizon's mu +- 1e-6 with it. Results are total (no NaN for finite input) and
// clamped: distances at 0.
#ifndef __cplusplus
#define real float
#endif

// r^2 (mu^2 - 1) + radius^2: negative when the ray's line misses the sphere.
real ray_sphere_discriminant_m2(real r_m, real mu, real radius_m) {
    real rm = r_m * mu;
    return (radius_m - r_m) * (radius_m + r_m) + rm * rm;
}
// Distance to the far intersection with the sphere (the exit, for an origin inside).
real ray_sphere_far_m(real r_m, real mu, real radius_m) {
    real d = sqrt(max(ray_sphere_discriminant_m2(r_m, mu, radius_m), 0.0));
    return max(-r_m * mu + d, 0.0);
}
// Distance to the near intersection with the sphere (the entry, for an origin outside; callers
// decide with ray_hits_sphere first whether there is one).
real ray_sphere_near_m(real r_m, real mu, real radius_m) {
    real d = sqrt(max(ray_sphere_discriminant_m2(r_m, mu, radius_m), 0.0));
    return max(-r_m * mu - d, 0.0);
}
// True when the ray meets the sphere going down: mu below the horizon's cosine
// -sqrt(1 - (radius / r)^2). A ray exactly at the horizon grazes and does not hit; from on or
// inside the sphere every downward ray hits it. Callers decide this once per ray and pass the
// flag on, as Bruneton 2017 does: deciding again from rounded (r, mu) can flip the answer.
bool ray_hits_sphere(real r_m, real mu, real radius_m) {
    return mu < 0.0 && (r_m <= radius_m || ray_sphere_discriminant_m2(r_m, mu, radius_m) > 0.0);
}
// Cosine of the zenith angle of the sphere's horizon seen from r_m: -sqrt(1 - (radius / r)^2),
// 0 on or inside the sphere. 1 - (R/r)^2 = (r - R)(r + R) / r^2, free of cancellation near it.
real ray_sphere_horizon_mu(real r_m, real radius_m) {
    if (r_m <= radius_m) return 0.0;
    return -sqrt((r_m - radius_m) * (r_m + radius_m)) / r_m;
}
// Distance to whichever boundary of the shell [bottom, top] the ray from inside it meets first.
real ray_shell_exit_m(real r_m, real mu, real bottom_m, real top_m) {
    return ray_hits_sphere(r_m, mu, bottom_m) ? ray_sphere_near_m(r_m, mu, bottom_m) : ray_sphere_far_m(r_m, mu, top_m);
}

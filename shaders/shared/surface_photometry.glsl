// How an airless surface reflects sunlight (shared by GLSL and C++): the lunar-Lambert function
// (McEwen 1991, section 2; its phase dependence from McEwen 1996).
//   radiance = albedo * E / pi * f(alpha) * lunar_lambert(cos_i, cos_e, L(alpha))
// A Lommel-Seeliger part 2 cos_i / (cos_i + cos_e), weighted by L, and a Lambert part cos_i,
// weighted by 1 - L. With L = 1 (the Moon at full phase) the disc is evenly bright out to its limb;
// with L = 0 the surface is Lambertian (every planet here). Both parts are 1 at normal incidence
// and emission, so the albedo keeps its meaning. The phase function f(alpha) is the CPU's (the
// measured disc-integrated curve over this function's disc integral: passes/planet_light).

// 0 where the Sun does not shine (cos_i <= 0); cos_e is clamped to the visible side.
float lunar_lambert(float cos_i, float cos_e, float limb_weight) {
    if (cos_i <= 0.0) {
        return 0.0;
    }
    float e = max(cos_e, 0.0);
    return limb_weight * 2.0 * cos_i / (cos_i + e) + (1.0 - limb_weight) * cos_i;
}

// McEwen's (1996) fit of L to the Moon's photometry, the phase angle alpha in radians:
// L = 1 - 0.019 a + 2.42e-4 a^2 - 1.46e-6 a^3 with a in degrees, kept within [0, 1] (it reaches 0
// near 104 degrees).
float lunar_lambert_limb_weight(float phase_rad) {
    float a = phase_rad * 57.29577951;
    return clamp(1.0 + a * (-0.019 + a * (2.42e-4 - 1.46e-6 * a)), 0.0, 1.0);
}

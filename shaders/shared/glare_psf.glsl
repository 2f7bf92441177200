// Sun glare: the scattered part of the eye's point-spread function (shared by GLSL and C++;
// GlareParams is in glare_types.glsl; needs constants.glsl and star_psf.glsl before it).
//
// Model: Spencer, Shirley, Zimmerman & Greenberg 1995, "Physically-based glare effects for
// digital images" (SIGGRAPH 95), the photopic PSF. With theta the angle from the source in
// DEGREES, the value is per STERADIAN, and the whole integrates to 1 over solid angle:
//   P(theta) = 0.384 f0 + 0.478 f1 + 0.138 f2
//   f0 = 2.61e6 exp(-(theta / 0.02)^2)   the image of the source itself
//   f1 = 20.91 / (theta + 0.02)^3        flare: ciliary corona and lenticular halo
//   f2 = 72.37 / (theta + 0.02)^2        bloom: veiling glare (scatter in the ocular media)
// Mixed units on purpose: the argument is in degrees, the solid angle in steradians
// (1 sr = (180/pi)^2 deg^2 = 3282.8 deg^2). Each f_i alone then integrates to about 1, so the
// weights are energy shares. Integrated numerically with the true element 2 pi sin(theta) dtheta
// (tests/test_glare_psf.cpp, GlarePsf.SpencerTermsIntegrateToTheirWeights):
//   0.384 f0: 0.384 x 0.9991
//   0.478 f1: 0.478 x 0.9991 out to 30 deg, x 0.9997 to 60, x 0.9999 to 90, x 1.0000 to 180
//             (small-angle, to infinity: 0.478 x 1.0005) -- the 1/theta^3 term converges
//   0.138 f2: 0.138 x 0.872 to 30 deg, x 0.958 to 60, x 0.981 to 74, x 0.99994 to 90,
//             x 1.033 to 180 -- the 1/theta^2 term does not converge; its weight holds for the
//             hemisphere (90 deg) with sin(theta), or to ~74 deg in the small-angle (flat) form
// Cupola draws the sun disc itself, so the glare here is only 0.478 f1 + 0.138 f2 (the 61.6 %
// of the light that the eye scatters). With the default 60-degree extent (fade from 51 deg) the
// drawn glare holds about 0.478 + 0.95 x 0.138 of the irradiance.
//
// On top of Spencer's radial profile, two angular features of the flare (its energy is moved
// around, never added): rays of the ciliary corona (glare_streaks, flickering slowly with the
// phase) and the coloured ring of the lenticular halo (glare_halo; its radius is a design value).
// Values are per steradian per unit irradiance: irradiance * glare_psf is a radiance.

// Spencer's flare and bloom terms with their weights, per sr; theta in radians, finite at 0.
float glare_bloom(float theta_rad) {
    float t = max(theta_rad, 0.0) * 57.29577951 + 0.02;  // degrees + 0.02
    return 0.138 * 72.37 / (t * t);
}

float glare_flare(float theta_rad) {
    float t = max(theta_rad, 0.0) * 57.29577951 + 0.02;
    return 0.478 * 20.91 / (t * t * t);
}

// A hash in [0, 1) for small integer-valued x (cell and pair indices), after Dave Hoskins'
// "Hash without Sine" (hash11). No sin, no integers, and each step is one correctly rounded
// float operation of a form that cannot fuse into an fma ((a + b) * c), with the constants in
// float variables (a C++ literal is double): GLSL and C++ give the same bits.
float glare_hash(float x) {
    float k1 = 0.1031;
    float k2 = 33.33;
    float p = fract(x * k1);
    p = p * (p + k2);
    p = p * (p + p);
    return fract(p);
}

// Angular modulation of the flare term: the rays of the ciliary corona. phi in radians (from
// atan(y, x), any range). The circle is cut into n cells (streak_count rounded to an even
// number, at least 2), starting at phi = 0; cell i holds one triangular ray of half-width 0.1
// cell at a hashed position in [0.1, 0.9] (so the ray never leaves its cell and the function is
// continuous everywhere, at phi = 0 and +-pi too: every cell boundary has the value 1 - c). The
// integral of the triangle over its cell is 0.1 cell. Rays come in neighbour pairs (2k, 2k+1)
// with brightness h = 0.5 +- 0.5 sin(2 pi (phase rate_k + offset_k)): the pair's sum is 1 at
// every phase, so the mean of h * tri over the circle is exactly 0.5 * 0.1 = 0.05 and
//   streaks = (1 - c) + c h tri / 0.05
// has mean exactly 1 over phi at every phase: the rays move the flare's energy, never add to it,
// and the animation never pulses the total.
// The number of rays: streak_count rounded to an even number, at least 2.
float glare_ray_cells(GlareParams p) { return max(2.0, 2.0 * floor(0.5 * p.streak_count + 0.5)); }

// Ray `cell` (an integer 0 .. glare_ray_cells - 1): its centre within the cell, in cells (in
// [0.1, 0.9]), and its brightness h at the phase, in [0, 1].
vec2 glare_ray(GlareParams p, float cell) {
    float centre = 0.1 + 0.8 * glare_hash(cell);
    float pair = floor(0.5 * cell);
    float sgn = (cell - 2.0 * pair) > 0.5 ? -1.0 : 1.0;
    float rate = 0.05 + 0.15 * glare_hash(pair + 317.0);  // cycles per unit phase
    float offset = glare_hash(pair + 631.0);
    // fract first: sin gets an argument in [0, 2 pi) whatever the phase (GPU sin is poor far out).
    float s = sin(2.0 * CUPOLA_PI * fract(p.phase * rate + offset));
    return vec2(centre, 0.5 + 0.5 * sgn * s);
}

float glare_streaks(GlareParams p, float phi_rad) {
    float n = glare_ray_cells(p);
    float c = clamp(p.streak_contrast, 0.0, 1.0);
    float x = fract(phi_rad * (0.5 / CUPOLA_PI)) * n;  // position in cells, [0, n]
    float cell = floor(x);
    float local = x - cell;  // [0, 1)
    vec2 ray = glare_ray(p, cell);
    float tri = max(0.0, 1.0 - abs(local - ray.x) * 10.0);
    return (1.0 - c) + c * ray.y * tri * 20.0;  // 20 = 1 / 0.05
}

// The rays' contrast where a ray is pixel_rad wide on the display: the rays are thin, and where
// one is narrower than about a pixel point sampling would alias it (shimmer as the glare moves),
// so its contrast fades there. The streaks' mean is 1 at any contrast, so the energy stays.
float glare_ray_contrast(GlareParams p, float theta_rad, float pixel_rad) {
    float ray_rad = theta_rad * (2.0 * CUPOLA_PI / max(p.streak_count, 2.0)) * 0.2;
    return p.streak_contrast * clamp((ray_rad / max(pixel_rad, 1e-9) - 0.5) / 1.5, 0.0, 1.0);
}

// A Gaussian ring of radius theta0_rad and sigma w_rad on the sphere, per sr, integral 1. The
// normalisation N = integral_0^pi exp(-(theta - theta0)^2 / 2 w^2) 2 pi sin(theta) dtheta is the
// flat (sin theta ~ theta) integral from 0, exact:
//   w^2 exp(-theta0^2 / 2 w^2) + sqrt(pi / 2) theta0 w (1 + erf(theta0 / (sqrt(2) w)))
// times the curvature factor (sin(theta0) / theta0) exp(-w^2 / 2), which is exact for a ring
// well away from the pole (the Gaussian over the whole line against sin). Good to ~w^2 / 6 at the
// pole, and to < 1e-3 in between for w <= 0.1 rad (tested to 1 %).
float glare_ring(float theta_rad, float theta0_rad, float w_rad) {
    float q = theta0_rad / w_rad;
    float planar = w_rad * w_rad * exp(-0.5 * q * q) + 1.25331414 * theta0_rad * w_rad * (1.0 + erf_approx(0.70710678 * q));
    float sinc = theta0_rad > 1e-6 ? sin(theta0_rad) / theta0_rad : 1.0;
    float norm = 2.0 * CUPOLA_PI * planar * sinc * exp(-0.5 * w_rad * w_rad);
    float d = (theta_rad - theta0_rad) / w_rad;
    return exp(-0.5 * d * d) / norm;
}

// The lenticular halo: one ring per colour sample, per sr, integral 1 per channel. The radius
// scales with wavelength (red 610 nm, green 550 nm, blue 465 nm; the ring is a diffraction
// pattern of the lens fibres), so red lies outside: the halo's rainbow. The width is the same for
// all three.
vec3 glare_halo(GlareParams p, float theta_rad) {
    float w = max(p.halo_width_rad, 1e-5);
    float r = max(p.halo_radius_rad, 0.0);
    return vec3(glare_ring(theta_rad, r * 1.10909091, w),  // 610 / 550
                glare_ring(theta_rad, r, w),
                glare_ring(theta_rad, r * 0.84545455, w));  // 465 / 550
}

// The glare PSF, rgb, per sr per unit irradiance of the source at the centre:
//   strength [bloom + flare (1 - hf) streaks + 0.478 hf halo] fade
// hf = halo_fraction: the ring takes that share of the flare term's energy (0.478 is the flare's
// total). fade is 1 inside 0.85 extent, falls smoothly (smoothstep) and is exactly 0 from the
// extent on. Finite at theta = 0.
vec3 glare_psf(GlareParams p, float theta_rad, float phi_rad) {
    if (theta_rad >= p.extent_rad) {
        return vec3(0.0);
    }
    float fade = 1.0 - smoothstep(0.85 * p.extent_rad, p.extent_rad, theta_rad);
    float hf = clamp(p.halo_fraction, 0.0, 1.0);
    float radial = glare_bloom(theta_rad) + glare_flare(theta_rad) * (1.0 - hf) * glare_streaks(p, phi_rad);
    vec3 rgb = vec3(radial) + glare_halo(p, theta_rad) * (0.478 * hf);
    return rgb * (p.strength * fade);
}

// Radiance of the glare seen along the unit direction v, for a source of the given irradiance
// (rgb) at the unit direction center. e1, e2: unit axes perpendicular to center, the glare frame
// shared by the whole cluster (phi = 0 along e1). theta from the chord (exact for tiny angles),
// so the result depends on the direction alone: every channel that sees v gets the same value.
vec3 glare_radiance(GlareParams p, vec3 v, vec3 center, vec3 e1, vec3 e2, vec3 irradiance) {
    float theta = angle_between_units(v, center);
    if (theta >= p.extent_rad) {
        return vec3(0.0);
    }
    float x = dot(v, e1);
    float y = dot(v, e2);
    float phi = (abs(x) + abs(y) > 1e-20) ? atan(y, x) : 0.0;  // GLSL's atan(0, 0) is undefined
    return irradiance * glare_psf(p, theta, phi);
}

// The glare split for drawing at two resolutions (slave/passes/glare_halo_pass.hpp): glare_psf
// is exactly
//   glare_psf_smooth(p, theta) + glare_ray_peak(p, theta) * h * tri
// with h and tri of the ray at phi (glare_streaks): the smooth part has no azimuth at all, the
// rays are nonzero only inside their wedges (a fifth of the circle).
vec3 glare_psf_smooth(GlareParams p, float theta_rad) {
    if (theta_rad >= p.extent_rad) {
        return vec3(0.0);
    }
    float fade = 1.0 - smoothstep(0.85 * p.extent_rad, p.extent_rad, theta_rad);
    float hf = clamp(p.halo_fraction, 0.0, 1.0);
    float c = clamp(p.streak_contrast, 0.0, 1.0);
    float radial = glare_bloom(theta_rad) + glare_flare(theta_rad) * (1.0 - hf) * (1.0 - c);
    vec3 rgb = vec3(radial) + glare_halo(p, theta_rad) * (0.478 * hf);
    return rgb * (p.strength * fade);
}

// The rays' radiance per unit h * tri (see glare_psf_smooth).
float glare_ray_peak(GlareParams p, float theta_rad) {
    if (theta_rad >= p.extent_rad) {
        return 0.0;
    }
    float fade = 1.0 - smoothstep(0.85 * p.extent_rad, p.extent_rad, theta_rad);
    float hf = clamp(p.halo_fraction, 0.0, 1.0);
    float c = clamp(p.streak_contrast, 0.0, 1.0);
    return glare_flare(theta_rad) * (1.0 - hf) * c * 20.0 * p.strength * fade;
}

// The core's share of the smooth part at theta: 1 inside inner_rad, falling smoothly
// (smoothstep) to exactly 0 from outer_rad on. The halo (drawn at reduced resolution) takes the
// rest, so that what is drawn at reduced resolution is zero near the source, where the PSF is
// steep, and varies slowly where it is not.
float glare_core_share(float theta_rad, float inner_rad, float outer_rad) {
    return 1.0 - smoothstep(inner_rad, outer_rad, theta_rad);
}

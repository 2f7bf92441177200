// A star's angular point spread function (shared by GLSL and C++).
// Gaussian in the angle a from the star's direction, normalised over the sphere, so that
// flux * star_psf(a, sigma) is a radiance whose integral over solid angle is flux:
//   integral_0^pi exp(-a^2 / 2 sigma^2) 2 pi sin(a) da = 2 pi sigma^2 (1 - sigma^2/3 + O(sigma^4))
// The sizes are cluster-wide angles, never pixels: every channel shows the same star.
float star_psf(float angle_rad, float sigma_rad) {
    float s2 = sigma_rad * sigma_rad;
    float norm = 2.0 * CUPOLA_PI * s2 * (1.0 - s2 / 3.0);
    return exp(-0.5 * angle_rad * angle_rad / s2) / norm;
}

// Angle between two unit vectors, accurate for tiny angles in float (acos(dot) is not: at
// 1 arcminute cos differs from 1 by 4e-8, below float resolution).
float angle_between_units(vec3 a, vec3 b) {
    return 2.0 * asin(clamp(0.5 * length(a - b), 0.0, 1.0));
}

// erf(x), Abramowitz & Stegun 7.1.26: |error| <= 1.5e-7.
float erf_approx(float x) {
    float a = abs(x);
    float t = 1.0 / (1.0 + 0.3275911 * a);
    float poly = ((((1.061405429 * t - 1.453152027) * t + 1.421413741) * t - 0.284496736) * t + 0.254829592) * t;
    float y = 1.0 - poly * exp(-a * a);
    return x < 0.0 ? -y : y;
}

// The star PSF seen in a channel's tangent plane (gnomonic coordinates x/-z, y/-z). Near a star at
// tangent point t the angular metric is ds^2 = ((1+|t|^2)|dt|^2 - (t.dt)^2) / (1+|t|^2)^2, so an
// angular sigma becomes these per-axis tangent-plane sigmas (the small cross term is dropped: it
// changes the star's shape slightly off axis, never its centre or its total energy).
vec2 star_tangent_sigma(vec2 t, float sigma_rad) {
    float q = 1.0 + t.x * t.x + t.y * t.y;
    float gxx = (q - t.x * t.x) / (q * q);
    float gyy = (q - t.y * t.y) / (q * q);
    return vec2(sigma_rad / sqrt(gxx), sigma_rad / sqrt(gyy));
}

// Fraction of a star's energy that falls in the tangent-plane box [lo, hi]: the exact integral
// of the (separable) Gaussian over the pixel, so a star smaller than a pixel keeps its energy and
// its centroid at any resolution. Summed over all pixels it is 1.
float star_box_fraction(vec2 t, vec2 sigma_t, vec2 lo, vec2 hi) {
    float kx = 0.70710678 / sigma_t.x;
    float ky = 0.70710678 / sigma_t.y;
    float fx = 0.5 * (erf_approx((hi.x - t.x) * kx) - erf_approx((lo.x - t.x) * kx));
    float fy = 0.5 * (erf_approx((hi.y - t.y) * ky) - erf_approx((lo.y - t.y) * ky));
    return fx * fy;
}

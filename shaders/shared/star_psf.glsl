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

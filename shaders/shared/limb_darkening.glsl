// Linear limb-darkening law for a stellar disc (shared by GLSL and C++).
// mu = cos of the angle between the surface normal and the line of sight (1 at the disc centre,
// 0 at the limb); u = linear coefficient (about 0.6 for the Sun in V).
//   I(mu) / I(1) = 1 - u (1 - mu)
float limb_darkening(float mu, float u) {
    return 1.0 - u * (1.0 - clamp(mu, 0.0, 1.0));
}

// Mean of limb_darkening over the projected disc: 2 * integral_0^1 (1 - u(1 - mu)) mu dmu = 1 - u/3.
// The irradiance at distance d from a sphere of radius R and centre radiance L is
// pi * L * (1 - u/3) * (R/d)^2.
float limb_darkening_disc_average(float u) {
    return 1.0 - u / 3.0;
}

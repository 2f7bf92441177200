// Local optical properties of the production atmosphere (shared by GLSL and C++; the
// AtmosphereParams struct is in atmosphere_types.glsl). Three sample wavelengths per vec3.
// Radiance is computed per unit solar irradiance at each sample wavelength; the model's colour
// matrix (production_model.cpp) turns that into photometric linear sRGB with the solar spectrum.

// Density profiles in [0, 1] at altitude h above the ground.
float atm_rayleigh_density(AtmosphereParams a, float h_m) {
    return exp(-max(h_m, 0.0) / a.rayleigh_scale_height_m);
}
float atm_mie_density(AtmosphereParams a, float h_m) {
    return exp(-max(h_m, 0.0) / a.mie_scale_height_m);
}
float atm_ozone_density(AtmosphereParams a, float h_m) {
    if (h_m <= a.ozone_bottom_m || h_m >= a.ozone_top_m) return 0.0;
    if (h_m < a.ozone_peak_m) return (h_m - a.ozone_bottom_m) / (a.ozone_peak_m - a.ozone_bottom_m);
    return (a.ozone_top_m - h_m) / (a.ozone_top_m - a.ozone_peak_m);
}

// Extinction coefficient (m^-1) at altitude h.
vec3 atm_extinction(AtmosphereParams a, float h_m) {
    return a.rayleigh_scattering_per_m * atm_rayleigh_density(a, h_m) + a.mie_extinction_per_m * atm_mie_density(a, h_m) +
           a.ozone_absorption_per_m * atm_ozone_density(a, h_m);
}
// Total scattering coefficient (m^-1) at altitude h (Rayleigh + Mie).
vec3 atm_scattering(AtmosphereParams a, float h_m) {
    return a.rayleigh_scattering_per_m * atm_rayleigh_density(a, h_m) + a.mie_scattering_per_m * atm_mie_density(a, h_m);
}

// Phase functions (per steradian), nu = cos(scattering angle).
float atm_rayleigh_phase(float nu) {
    return 3.0 / (16.0 * CUPOLA_PI) * (1.0 + nu * nu);
}
float atm_cornette_shanks_phase(float g, float nu) {
    float k = 3.0 / (8.0 * CUPOLA_PI) * (1.0 - g * g) / (2.0 + g * g);
    float denom = max(1.0 + g * g - 2.0 * g * nu, 1e-12);
    return k * (1.0 + nu * nu) / (denom * sqrt(denom));
}

// (1 - exp(-x)) / x per component, accurate for small x (the energy-conserving step weight).
vec3 atm_one_minus_exp_over_x(vec3 x) {
    vec3 big = (vec3(1.0) - exp(-x)) / max(x, 1e-30);
    vec3 small = vec3(1.0) - x * 0.5 + x * x * (1.0 / 6.0);
    return mix(small, big, step(vec3(1e-3), x));
}

// The fast analytic atmosphere of UniView (Ekelin & Fernqvist 2009, sections 2.4.3 and 3.2.1, after
// Hoffman & Preetham 2002 and Stokholm Nielsen 2003),
// shared by GLSL and C++. One scale height for both species; optical depth from the mean density
// of three points (start, middle, end) times the path length; in-scatter
//   L_in = (b_R F_R + b_M F_M) / (b_R + b_M) * E_sun * (1 - exp(-(b_R + b_M) S)),
// with E_sun = 1 / sqrt(1 + (alpha / k1)^k2) a non-physical fit of the sunlight reaching the air
// (alpha = angle between the local vertical at the ray's midpoint and the Sun). k1 (per
// wavelength) and k2 are fitted to the model's own transmittance on the CPU
// (production_model.cpp) instead of being hand-tuned. Per unit solar irradiance, like atm_march.


vec3 atm_analytic_sun(AtmosphereAnalyticFit fit, float mu_s) {
    float alpha = acos(clamp(mu_s, -1.0, 1.0));
    vec3 x = vec3(alpha) / fit.k1_rad;
    return vec3(1.0) / sqrt(vec3(1.0) + pow(x, vec3(fit.k2)));
}

AtmosphereSegment atm_analytic(AtmosphereParams a, AtmosphereAnalyticFit fit, float r_m, float mu, float mu_s, float nu,
                               float t_end_m) {
    AtmosphereSegment s;
    s.inscatter_per_sr = vec3(0.0);
    s.transmittance = vec3(1.0);
    if (t_end_m <= 0.0) return s;
    float H = a.rayleigh_scale_height_m;
    float r_mid = atm_radius_at(r_m, mu, 0.5 * t_end_m);
    float r_end = atm_radius_at(r_m, mu, t_end_m);
    float rho = (exp(-(r_m - a.bottom_radius_m) / H) + exp(-(r_mid - a.bottom_radius_m) / H) +
                 exp(-(r_end - a.bottom_radius_m) / H)) / 3.0;
    float depth = rho * t_end_m;
    vec3 beta_r = a.rayleigh_scattering_per_m;
    vec3 beta_m = a.mie_extinction_per_m;
    vec3 f_ext = exp(-(beta_r + beta_m) * depth);
    vec3 phase = (beta_r * atm_rayleigh_phase(nu) + a.mie_scattering_per_m * atm_cornette_shanks_phase(a.mie_g, nu)) /
                 (beta_r + beta_m);
    s.inscatter_per_sr = phase * atm_analytic_sun(fit, atm_mu_s_at(r_m, mu_s, nu, 0.5 * t_end_m, r_mid)) * (vec3(1.0) - f_ext);
    s.transmittance = f_ext;
    return s;
}

// The fast model over a whole camera ray, ended like atm_view_ray.
AtmosphereSegment atm_analytic_view_ray(AtmosphereParams a, AtmosphereAnalyticFit fit, AtmosphereRayStart st,
                                        float t_geometry_m) {
    return atm_analytic(a, fit, st.r_m, st.mu, st.mu_s, st.nu, atm_view_ray_length(a, st, t_geometry_m));
}

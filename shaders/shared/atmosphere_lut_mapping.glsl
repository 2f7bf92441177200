// Texture-coordinate <-> parameter mappings of the production tables (shared by GLSL and C++).
// Texel centres map to the ends of each parameter range (Bruneton 2017), so table edges hold the
// exact boundary values. Every mapping has its inverse here; tests check both directions.

float atm_texcoord_from_unit(float x, float n) {
    return 0.5 / n + x * (1.0 - 1.0 / n);
}
float atm_unit_from_texcoord(float u, float n) {
    return (u - 0.5 / n) / (1.0 - 1.0 / n);
}

// Transmittance table: (r, mu) for rays that reach the top (Bruneton 2017's mapping: x_r is the
// distance to the horizon, x_mu the distance to the top, both normalised).
vec2 atm_transmittance_uv(AtmosphereParams a, float r_m, float mu, vec2 size) {
    float H = sqrt((a.top_radius_m - a.bottom_radius_m) * (a.top_radius_m + a.bottom_radius_m));
    float rho = sqrt(max((r_m - a.bottom_radius_m) * (r_m + a.bottom_radius_m), 0.0));
    float d = atm_distance_to_top(a, r_m, mu);
    float d_min = a.top_radius_m - r_m;
    float d_max = rho + H;
    float x_mu = (d_max > d_min) ? (d - d_min) / (d_max - d_min) : 0.0;  // no 0/0 for a degenerate range
    float x_r = rho / H;
    return vec2(atm_texcoord_from_unit(clamp(x_mu, 0.0, 1.0), size.x),
                atm_texcoord_from_unit(clamp(x_r, 0.0, 1.0), size.y));
}
// Inverse: (r, mu) of a texture coordinate.
vec2 atm_transmittance_r_mu(AtmosphereParams a, vec2 uv, vec2 size) {
    float x_mu = atm_unit_from_texcoord(uv.x, size.x);
    float x_r = atm_unit_from_texcoord(uv.y, size.y);
    float H = sqrt((a.top_radius_m - a.bottom_radius_m) * (a.top_radius_m + a.bottom_radius_m));
    float rho = H * x_r;
    float r = sqrt(rho * rho + a.bottom_radius_m * a.bottom_radius_m);
    float d_min = a.top_radius_m - r;
    float d_max = rho + H;
    float d = d_min + x_mu * (d_max - d_min);
    // H^2 - rho^2 = top^2 - r^2, formed as a product (no float cancellation).
    float mu = (d == 0.0) ? 1.0 : ((a.top_radius_m - r) * (a.top_radius_m + r) - d * d) / (2.0 * r * d);
    return vec2(r, clamp(mu, -1.0, 1.0));
}

// Multiple-scattering and ground-irradiance tables: (mu_s, r). r is linear; mu_s goes through a
// signed square root, x = 1/2 + sign(mu_s) sqrt(|mu_s|) / 2, which puts the texels where these
// quantities change fastest -- the Sun near the horizon (twilight) -- at ~16x the density of a
// linear mapping (Hillaire 2020 maps mu_s linearly).
vec2 atm_ms_uv(AtmosphereParams a, float r_m, float mu_s, vec2 size) {
    float m = clamp(mu_s, -1.0, 1.0);
    float x_mu_s = 0.5 + 0.5 * sign(m) * sqrt(abs(m));
    float x_r = (r_m - a.bottom_radius_m) / (a.top_radius_m - a.bottom_radius_m);
    return vec2(atm_texcoord_from_unit(clamp(x_mu_s, 0.0, 1.0), size.x),
                atm_texcoord_from_unit(clamp(x_r, 0.0, 1.0), size.y));
}
vec2 atm_ms_r_mu_s(AtmosphereParams a, vec2 uv, vec2 size) {
    float x_mu_s = atm_unit_from_texcoord(uv.x, size.x);
    float x_r = atm_unit_from_texcoord(uv.y, size.y);
    float s = 2.0 * x_mu_s - 1.0;
    return vec2(a.bottom_radius_m + x_r * (a.top_radius_m - a.bottom_radius_m), clamp(sign(s) * s * s, -1.0, 1.0));
}

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
vec2 atm_transmittance_uv(AtmosphereParams a, float r, float mu, vec2 size) {
    float H = sqrt(a.top_radius * a.top_radius - a.bottom_radius * a.bottom_radius);
    float rho = sqrt(max(r * r - a.bottom_radius * a.bottom_radius, 0.0));
    float d = atm_distance_to_top(a, r, mu);
    float d_min = a.top_radius - r;
    float d_max = rho + H;
    float x_mu = (d_max > d_min) ? (d - d_min) / (d_max - d_min) : 0.0;  // hard case 4
    float x_r = rho / H;
    return vec2(atm_texcoord_from_unit(clamp(x_mu, 0.0, 1.0), size.x),
                atm_texcoord_from_unit(clamp(x_r, 0.0, 1.0), size.y));
}
// Inverse: (r, mu) of a texture coordinate.
vec2 atm_transmittance_r_mu(AtmosphereParams a, vec2 uv, vec2 size) {
    float x_mu = atm_unit_from_texcoord(uv.x, size.x);
    float x_r = atm_unit_from_texcoord(uv.y, size.y);
    float H = sqrt(a.top_radius * a.top_radius - a.bottom_radius * a.bottom_radius);
    float rho = H * x_r;
    float r = sqrt(rho * rho + a.bottom_radius * a.bottom_radius);
    float d_min = a.top_radius - r;
    float d_max = rho + H;
    float d = d_min + x_mu * (d_max - d_min);
    float mu = (d == 0.0) ? 1.0 : (H * H - rho * rho - d * d) / (2.0 * r * d);
    return vec2(r, clamp(mu, -1.0, 1.0));
}

// Multiple-scattering and ground-irradiance tables: (mu_s, r), linear in both (Hillaire 2020).
vec2 atm_ms_uv(AtmosphereParams a, float r, float mu_s, vec2 size) {
    float x_mu_s = mu_s * 0.5 + 0.5;
    float x_r = (r - a.bottom_radius) / (a.top_radius - a.bottom_radius);
    return vec2(atm_texcoord_from_unit(clamp(x_mu_s, 0.0, 1.0), size.x),
                atm_texcoord_from_unit(clamp(x_r, 0.0, 1.0), size.y));
}
vec2 atm_ms_r_mu_s(AtmosphereParams a, vec2 uv, vec2 size) {
    float x_mu_s = atm_unit_from_texcoord(uv.x, size.x);
    float x_r = atm_unit_from_texcoord(uv.y, size.y);
    return vec2(a.bottom_radius + x_r * (a.top_radius - a.bottom_radius), clamp(x_mu_s * 2.0 - 1.0, -1.0, 1.0));
}

// The production model's precomputed tables: what one texel holds and how it is computed, plus
// the lookups (shared by GLSL and C++; the CPU builds the tables with threads, see
// common/atmosphere/production_tables.cpp). All tables are per unit solar irradiance.
//
//  transmittance  T(r, mu) to the top of the atmosphere, for rays that do not meet the ground.
//  multiple_scattering  Psi_ms(r, mu_s) (after Hillaire 2020): the in-scattered radiance of orders
//                 >= 2 per unit scattering coefficient, isotropic: the sum of J_2 .. J_N, each
//                 order computed from the previous one's table (ms_orders), or J_2 / (1 - f_ms)
//                 (Hillaire's geometric tail) when ms_orders is 0. Alpha: the Rayleigh anisotropy
//                 ratio of the arriving light (atm_ms_rayleigh_factor), or 0.
//  irradiance     E_sky(r, mu_s): sky irradiance on a horizontal surface (orders >= 1 from the
//                 sky, not the direct Sun), for the ground's sky light.

vec3 atm_lookup_transmittance(AtmosphereParams a, sampler2D table, vec2 size, float r_m, float mu) {
    return vec3(textureLod(table, atm_transmittance_uv(a, r_m, mu, size), 0.0));
}
// Transmittance toward the Sun from (r, mu_s): 0 when the ground hides the (point) Sun.
vec3 atm_sun_transmittance(AtmosphereParams a, sampler2D table, vec2 size, float r_m, float mu_s) {
    if (atm_ray_hits_ground(a, r_m, mu_s)) return vec3(0.0);
    return atm_lookup_transmittance(a, table, size, r_m, mu_s);
}
vec3 atm_lookup_ms(AtmosphereParams a, sampler2D table, vec2 size, float r_m, float mu_s) {
    return vec3(textureLod(table, atm_ms_uv(a, r_m, mu_s, size), 0.0));
}
// The whole multiple-scattering texel: Psi_ms in rgb, the Rayleigh anisotropy ratio in alpha (see
// atm_compute_ms).
vec4 atm_lookup_ms_moment(AtmosphereParams a, sampler2D table, vec2 size, float r_m, float mu_s) {
    return textureLod(table, atm_ms_uv(a, r_m, mu_s, size), 0.0);
}
// Legendre polynomial P2(c) = (3 c^2 - 1) / 2. The Rayleigh phase is (1 + P2(nu) / 2) / (4 pi).
float atm_legendre_p2(float c) {
    return 1.5 * c * c - 0.5;
}
// Factor on the Rayleigh part of the multiple scattering for a view at nu = cos(view, sun), from
// the texel's anisotropy ratio k (alpha): the light arriving at the point from the first
// scattering is not isotropic, and the Rayleigh phase of the next scattering weights it. With the
// arriving radiance taken symmetric about the Sun direction, the integral of L times the Rayleigh
// phase is Psi_ms (1 + k P2(nu) / 2), k = the P2(cos to the Sun) moment of L over its mean (the
// addition theorem of spherical harmonics). Hillaire 2020 (section 5.1) takes the whole term
// isotropic; Mie's part stays so. k is 0 in tables built without ms_rayleigh_anisotropy.
float atm_ms_rayleigh_factor(float k, float nu) {
    return max(1.0 + 0.5 * k * atm_legendre_p2(nu), 0.0);
}
vec3 atm_lookup_irradiance(AtmosphereParams a, sampler2D table, vec2 size, float r_m, float mu_s) {
    return vec3(textureLod(table, atm_ms_uv(a, r_m, mu_s, size), 0.0));
}

// Transmittance texel: optical depth to the top by the midpoint rule in `steps` steps.
vec3 atm_compute_transmittance(AtmosphereParams a, float r_m, float mu, int steps) {
    float len = atm_distance_to_top(a, r_m, mu);
    float dt = len / float(steps);
    vec3 tau = vec3(0.0);
    for (int i = 0; i < steps; ++i) {
        float t = (float(i) + 0.5) * dt;
        float h = atm_radius_at(r_m, mu, t) - a.bottom_radius_m;
        tau = tau + atm_extinction(a, h) * dt;
    }
    return exp(-tau);
}

// Radiance (per unit solar irradiance) scattered once toward a point from direction (mu, nu)
// [Hillaire's L'], and the transfer factor f_ms along that direction.
AtmosphereMsTerms atm_ms_terms_along(AtmosphereParams a, sampler2D trans, vec2 trans_size, float r_m, float mu,
                                     float mu_s, float nu, int steps) {
    AtmosphereMsTerms out_terms;
    out_terms.second_order_per_sr = vec3(0.0);
    out_terms.transfer = vec3(0.0);
    bool ground = atm_ray_hits_ground(a, r_m, mu);
    float len = ground ? atm_distance_to_ground(a, r_m, mu) : atm_distance_to_top(a, r_m, mu);
    float dt = len / float(steps);
    vec3 throughput = vec3(1.0);
    for (int i = 0; i < steps; ++i) {
        float t = (float(i) + 0.5) * dt;
        float r_t = atm_radius_at(r_m, mu, t);
        float h = r_t - a.bottom_radius_m;
        float dr = atm_rayleigh_density(a, h);
        float dm = atm_mie_density(a, h);
        vec3 sigma_s = a.rayleigh_scattering_per_m * dr + a.mie_scattering_per_m * dm;
        vec3 sigma_t = atm_extinction(a, h);
        vec3 w = throughput * atm_one_minus_exp_over_x(sigma_t * dt) * dt;  // integral of T over the step
        vec3 t_sun = atm_sun_transmittance(a, trans, trans_size, r_t, atm_mu_s_at(r_m, mu_s, nu, t, r_t));
        // First scattering with the true phase functions (sunlight turned from -sun into -w: the
        // cosine of that angle is nu); only the second scattering, at the table point, is taken
        // isotropic. (Hillaire 2020 takes both isotropic, which overestimates twilight, where
        // sunlight reaches the shadowed air only through ~90-degree Rayleigh scattering.)
        vec3 phase_weighted = a.rayleigh_scattering_per_m * (dr * atm_rayleigh_phase(nu)) +
                              a.mie_scattering_per_m * (dm * atm_cornette_shanks_phase(a.mie_g, nu));
        out_terms.second_order_per_sr = out_terms.second_order_per_sr + w * phase_weighted * t_sun;
        out_terms.transfer = out_terms.transfer + w * sigma_s;
        throughput = throughput * exp(-sigma_t * dt);
    }
    if (ground) {
        float r_g = a.bottom_radius_m;
        float mu_s_g = atm_mu_s_at(r_m, mu_s, nu, len, max(atm_radius_at(r_m, mu, len), r_g));
        vec3 t_sun = atm_sun_transmittance(a, trans, trans_size, r_g, mu_s_g);
        out_terms.second_order_per_sr =
            out_terms.second_order_per_sr + throughput * t_sun * max(mu_s_g, 0.0) * a.ground_albedo / CUPOLA_PI;
    }
    return out_terms;
}

// Unit vector number i of n spread evenly over the sphere (spherical Fibonacci); z is "up".
vec3 atm_sphere_direction(int i, int n) {
    float z = 1.0 - (2.0 * float(i) + 1.0) / float(n);
    float phi = 2.39996322972865 * float(i);  // golden angle
    float s = sqrt(max(1.0 - z * z, 0.0));
    return vec3(s * cos(phi), s * sin(phi), z);
}

// Second-order texel: J_2 = integral over the sphere of L' times the isotropic phase 1/(4 pi);
// each direction carries the solid angle 4 pi / n, so the two factors cancel to 1/n. With
// geometric_tail, the orders >= 3 are added as Hillaire 2020 does: J_2 / (1 - f_ms), which
// assumes every point sees the same J as the table point (fine by day, ~2x too bright in
// twilight); without it, only J_2 (the builder adds orders >= 3 by atm_compute_ms_next_order).
// Alpha: the same integral weighted by P2 of the arriving light's cosine to the Sun (P2 is even:
// toward or from the Sun alike), at 550 nm; the builder divides it by the summed orders, for
// atm_ms_rayleigh_factor.
vec4 atm_compute_ms(AtmosphereParams a, sampler2D trans, vec2 trans_size, float r_m, float mu_s, int directions,
                    int steps, bool geometric_tail) {
    vec3 l2 = vec3(0.0);
    vec3 f = vec3(0.0);
    float moment = 0.0;
    float sin_s = sqrt(max(1.0 - mu_s * mu_s, 0.0));
    for (int i = 0; i < directions; ++i) {
        vec3 w = atm_sphere_direction(i, directions);
        float nu = w.x * sin_s + w.z * mu_s;  // Sun in the x-z plane
        AtmosphereMsTerms m = atm_ms_terms_along(a, trans, trans_size, r_m, w.z, mu_s, nu, steps);
        l2 = l2 + m.second_order_per_sr;
        f = f + m.transfer;
        moment = moment + m.second_order_per_sr.y * atm_legendre_p2(nu);
    }
    l2 = l2 * (1.0 / float(directions));
    f = f * (1.0 / float(directions));
    moment = moment * (1.0 / float(directions));
    if (!geometric_tail) return vec4(l2, moment);
    return vec4(l2 / max(vec3(1.0) - f, 1e-3), moment);
}

// Next-order texel: J_{n+1}(x) = 1/n sum over directions of the integral of T sigma_s J_n along
// the direction, J_n read from its table at each point (isotropic scattering, but J varying in
// space -- what the geometric tail assumes away). The ground's reflection of diffuse light is
// left out (albedo x sky irradiance: ~1 % of J by day).
vec3 atm_compute_ms_next_order(AtmosphereParams a, sampler2D jn, vec2 jn_size, float r_m, float mu_s, int directions,
                               int steps) {
    vec3 sum = vec3(0.0);
    float sin_s = sqrt(max(1.0 - mu_s * mu_s, 0.0));
    for (int i = 0; i < directions; ++i) {
        vec3 w = atm_sphere_direction(i, directions);
        float nu = w.x * sin_s + w.z * mu_s;
        bool ground = atm_ray_hits_ground(a, r_m, w.z);
        float len = ground ? atm_distance_to_ground(a, r_m, w.z) : atm_distance_to_top(a, r_m, w.z);
        float dt = len / float(steps);
        vec3 throughput = vec3(1.0);
        for (int k = 0; k < steps; ++k) {
            float t = (float(k) + 0.5) * dt;
            float r_t = atm_radius_at(r_m, w.z, t);
            float h = r_t - a.bottom_radius_m;
            vec3 sigma_t = atm_extinction(a, h);
            vec3 wt = throughput * atm_one_minus_exp_over_x(sigma_t * dt) * dt;
            sum = sum + wt * atm_scattering(a, h) * atm_lookup_ms(a, jn, jn_size, r_t, atm_mu_s_at(r_m, mu_s, nu, t, r_t));
            throughput = throughput * exp(-sigma_t * dt);
        }
    }
    return sum * (1.0 / float(directions));
}

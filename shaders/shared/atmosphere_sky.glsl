// The production sky model (shared by GLSL and C++): in-scattered radiance and transmittance
// along one view ray, by ray marching with the precomputed tables (Hillaire 2020's per-pixel
// path, usable from the ground to 1 AU). Per unit solar irradiance; the model's colour matrix
// converts the result to photometric linear sRGB.


// One march step: the in-scatter parts and the transmittance of the interval [t0, t1] through the
// sample at its midpoint; energy-conserving in each step (exact for constant coefficients).
// `light` scales the sunlight reaching the sample (eclipse shadows; 1 outside every shadow):
// single and multiple scattering alike, i.e. the air around a shadowed sample is taken to be
// shadowed the same way (the multiple-scattering table knows no shadows).
AtmosphereSplitSegment atm_march_interval(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms,
                                          vec2 ms_size, bool use_ms, float r_m, float mu, float mu_s, float nu,
                                          float t0_m, float t1_m, vec3 throughput, vec3 light) {
    AtmosphereSplitSegment s;
    float dt = t1_m - t0_m;
    float t = 0.5 * (t0_m + t1_m);
    float r_t = atm_radius_at(r_m, mu, t);
    float h = r_t - a.bottom_radius_m;
    float mu_s_t = atm_mu_s_at(r_m, mu_s, nu, t, r_t);
    float dr = atm_rayleigh_density(a, h);
    float dm = atm_mie_density(a, h);
    vec3 sigma_t = a.rayleigh_scattering_per_m * dr + a.mie_extinction_per_m * dm + a.ozone_absorption_per_m * atm_ozone_density(a, h);
    vec3 w = throughput * light * atm_one_minus_exp_over_x(sigma_t * dt) * dt;  // integral of T over the step
    vec3 lit = w * atm_sun_transmittance(a, trans, trans_size, r_t, mu_s_t);
    s.rayleigh_unphased = lit * a.rayleigh_scattering_per_m * dr;
    s.mie_unphased = lit * a.mie_scattering_per_m * dm;
    s.multiple_per_sr = vec3(0.0);
    if (use_ms) {
        vec4 psi = atm_lookup_ms_moment(a, ms, ms_size, r_t, mu_s_t);
        float rayleigh_factor = atm_ms_rayleigh_factor(psi.w, nu);
        s.multiple_per_sr = w * (a.rayleigh_scattering_per_m * (dr * rayleigh_factor) + a.mie_scattering_per_m * dm) * vec3(psi);
    }
    s.transmittance = exp(-sigma_t * dt);
    return s;
}

// The radiance of the parts for a view at nu = cos(view, sun): the phase functions applied.
vec3 atm_split_inscatter(AtmosphereParams a, AtmosphereSplitSegment s, float nu) {
    return s.rayleigh_unphased * atm_rayleigh_phase(nu) + s.mie_unphased * atm_cornette_shanks_phase(a.mie_g, nu) +
           s.multiple_per_sr;
}

// In-scatter parts and transmittance along the ray from (r_m, mu) over [0, t_end_m] in `samples`
// steps. The steps are concentrated (quadratically) toward the ray's closest approach to the
// planet centre, where the air is densest: t_c = -r mu clamped to the segment; each side gets a
// share of the steps proportional to its length, at least one. `shadow` (its casters may be none)
// dims the sunlight at each sample; `ecl_lut` is the eclipse table for its lookup-table mode.
AtmosphereSplitSegment atm_march_split(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms,
                                       vec2 ms_size, bool use_ms, float r_m, float mu, float mu_s, float nu,
                                       float t_end_m, int samples, EclipseRay shadow, sampler2D ecl_lut) {
    AtmosphereSplitSegment total;
    total.rayleigh_unphased = vec3(0.0);
    total.mie_unphased = vec3(0.0);
    total.multiple_per_sr = vec3(0.0);
    total.transmittance = vec3(1.0);
    if (t_end_m <= 0.0) return total;
    float t_c = clamp(-r_m * mu, 0.0, t_end_m);
    int n_before = 0;
    if (t_c > 0.0) n_before = int(clamp(floor(float(samples) * t_c / t_end_m + 0.5), 1.0, float(samples)));
    if (t_c < t_end_m && n_before == samples) n_before = samples - 1;
    int n_after = samples - n_before;
    float t_prev = 0.0;
    // Before t_c: t(u) = t_c (1 - (1 - u)^2); after: t(u) = t_c + (t_end_m - t_c) u^2; both dense
    // toward t_c.
    for (int i = 1; i <= samples; ++i) {
        float t_next;
        if (i <= n_before) {
            float u = float(i) / float(n_before);
            t_next = t_c * (1.0 - (1.0 - u) * (1.0 - u));
        } else {
            float u = float(i - n_before) / float(n_after);
            t_next = t_c + (t_end_m - t_c) * u * u;
        }
        AtmosphereSplitSegment s =
            atm_march_interval(a, trans, trans_size, ms, ms_size, use_ms, r_m, mu, mu_s, nu, t_prev, t_next, total.transmittance,
                               eclipse_light_along(shadow, ecl_lut, 0.5 * (t_prev + t_next)));
        total.rayleigh_unphased = total.rayleigh_unphased + s.rayleigh_unphased;
        total.mie_unphased = total.mie_unphased + s.mie_unphased;
        total.multiple_per_sr = total.multiple_per_sr + s.multiple_per_sr;
        total.transmittance = total.transmittance * s.transmittance;
        t_prev = t_next;
    }
    return total;
}

// The same with the phase functions applied: in-scatter and transmittance.
AtmosphereSegment atm_march(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms, vec2 ms_size,
                            bool use_ms, float r_m, float mu, float mu_s, float nu, float t_end_m, int samples,
                            EclipseRay shadow, sampler2D ecl_lut) {
    AtmosphereSplitSegment s = atm_march_split(a, trans, trans_size, ms, ms_size, use_ms, r_m, mu, mu_s, nu, t_end_m,
                                               samples, shadow, ecl_lut);
    AtmosphereSegment total;
    total.inscatter_per_sr = atm_split_inscatter(a, s, nu);
    total.transmittance = s.transmittance;
    return total;
}

// Illuminance factor of a horizontal surface at (r, mu_s) per unit solar irradiance: direct Sun
// through the atmosphere plus sky light. Reflected radiance = albedo / pi * this.
vec3 atm_surface_illuminance(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D irr, vec2 irr_size,
                             float r_m, float mu_s) {
    vec3 direct = atm_sun_transmittance(a, trans, trans_size, r_m, mu_s) * max(mu_s, 0.0);
    return direct + atm_lookup_irradiance(a, irr, irr_size, r_m, mu_s);
}

// Irradiance texel: the sky (single + multiple scattering, no ground bounce) integrated over
// the upper hemisphere with the cosine weight, `directions` directions, `samples` steps each.
vec3 atm_compute_irradiance(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms, vec2 ms_size,
                            bool use_ms, float r_m, float mu_s, int directions, int samples) {
    vec3 e = vec3(0.0);
    float sin_s = sqrt(max(1.0 - mu_s * mu_s, 0.0));
    for (int i = 0; i < directions; ++i) {
        vec3 w = atm_sphere_direction(i, 2 * directions);  // the first half has z > 0
        float nu = w.x * sin_s + w.z * mu_s;
        float len = atm_distance_to_top(a, r_m, w.z);
        AtmosphereSegment s = atm_march(a, trans, trans_size, ms, ms_size, use_ms, r_m, w.z, mu_s, nu, len, samples,
                                        eclipse_ray(eclipse_no_casters(), vec2(1.0), vec3(0.0), vec3(0.0)), trans);
        e = e + s.inscatter_per_sr * w.z;
    }
    return e * (2.0 * CUPOLA_PI / float(directions));
}

// Length of the atmospheric part of a camera ray (see atm_ray_start), from its start: to the
// ground, the top of the atmosphere, or scene geometry t_geometry_m from the camera
// (t_geometry_m < 0: none); 0 when the ray misses the atmosphere. Every model ends rays here.
float atm_view_ray_length(AtmosphereParams a, AtmosphereRayStart st, float t_geometry_m) {
    if (!st.valid) return 0.0;
    bool ground = atm_ray_hits_ground(a, st.r_m, st.mu);
    float t_end = ground ? atm_distance_to_ground(a, st.r_m, st.mu) : atm_distance_to_top(a, st.r_m, st.mu);
    if (t_geometry_m >= 0.0) t_end = min(t_end, max(t_geometry_m - st.offset_m, 0.0));
    return t_end;
}

// A whole view ray from a camera: in-scatter and transmittance over atm_view_ray_length, with
// the sunlight dimmed by the planet's eclipse shadows; shadow.origin_m is the ray's start (the
// camera moved st.offset along v), relative to the planet centre, and shadow.dir = v.
AtmosphereSegment atm_view_ray_shadowed(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms,
                                        vec2 ms_size, bool use_ms, AtmosphereRayStart st, float t_geometry_m,
                                        int samples, EclipseRay shadow, sampler2D ecl_lut) {
    return atm_march(a, trans, trans_size, ms, ms_size, use_ms, st.r_m, st.mu, st.mu_s, st.nu,
                     atm_view_ray_length(a, st, t_geometry_m), samples, shadow, ecl_lut);
}

// The same without shadows.
AtmosphereSegment atm_view_ray(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms, vec2 ms_size,
                               bool use_ms, AtmosphereRayStart st, float t_geometry_m, int samples) {
    return atm_view_ray_shadowed(a, trans, trans_size, ms, ms_size, use_ms, st, t_geometry_m, samples,
                                 eclipse_ray(eclipse_no_casters(), vec2(1.0), vec3(0.0), vec3(0.0)), trans);
}

// Distance from the camera to the ground along the ray, or -1 when it does not meet the ground.
float atm_ground_distance(AtmosphereParams a, AtmosphereRayStart st) {
    if (!st.valid || !atm_ray_hits_ground(a, st.r_m, st.mu)) return -1.0;
    return st.offset_m + atm_distance_to_ground(a, st.r_m, st.mu);
}

// Radiance leaving the ground (albedo from the parameters) where the ray meets it, per unit solar
// irradiance, before the view ray's transmittance.
vec3 atm_ground_radiance(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D irr, vec2 irr_size,
                         AtmosphereRayStart st, vec3 albedo) {
    float t = atm_distance_to_ground(a, st.r_m, st.mu);
    float mu_s_g = atm_mu_s_at(st.r_m, st.mu_s, st.nu, t, max(atm_radius_at(st.r_m, st.mu, t), a.bottom_radius_m));
    return albedo * (1.0 / CUPOLA_PI) *
           atm_surface_illuminance(a, trans, trans_size, irr, irr_size, a.bottom_radius_m, mu_s_g);
}

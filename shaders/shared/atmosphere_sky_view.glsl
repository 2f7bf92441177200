// The sky-view table (after Hillaire 2020, section 5): the atmosphere's light for every view
// direction from one camera position, computed once per frame into a small table and looked up
// per pixel (shared by GLSL and C++). It depends only on the camera's distance from the planet
// centre and the Sun's zenith angle there, never on a channel's frustum, so every channel of a
// dome computes the same table and the sky is seamless by construction.
//
// Layout: W x H texels, H even. Rows [0, H/2) hold the rays that meet the ground, rows [H/2, H)
// the rays that do not; a lookup stays inside its half (the ray's ground flag, decided once, picks
// it), so no texel ever blends the sky with the ground across the horizon. Within a half the row
// coordinate x runs from 0 at the horizon (the limb, seen from outside) to 1 and is taken through
// a square root, which puts the rows where the light changes fastest:
//   camera inside the atmosphere, view zenith cosine mu, horizon mu_h < 0:
//     sky    mu = mu_h + (1 - mu_h) x^2           ground mu = mu_h - (1 + mu_h) x^2
//   camera outside, impact parameter rho (distance of the ray's line from the centre):
//     sky    rho = R + (top - R) x^2 (3 - 2 x)   ground rho = R (1 - x^2)
// (the sky's rows seen from outside are dense at both ends: at the limb, and where the rays
// graze the top of the atmosphere and their light falls to 0 over the last few kilometres).
// Columns: the azimuth phi in [0, pi] between the view and the Sun about the camera's zenith (the
// atmosphere is symmetric about the plane of the zenith and the Sun), as sin(phi / 2), which keeps
// the columns dense toward the Sun. Texel centres sit on the ends of each range (Bruneton 2017),
// as in atmosphere_lut_mapping.glsl. Inside the atmosphere every coordinate comes from cosines
// and square roots: a pixel's look-up needs no inverse trigonometric function.
//
// A texel holds linear sRGB per unit solar irradiance (times the scene's solar scale, scene units):
//   0  single Rayleigh scattering with its phase at the texel's nu, plus the multiple scattering;
//   1  single Mie scattering without its phase: the pixel multiplies it by the Cornette-Shanks
//      phase of its own nu, so the Sun's aureole is as sharp as the pixels, not the table;
//   2  sky half: the effective transmittance to the top of the atmosphere of sunlight-coloured
//      light, per sRGB channel (what lies beyond the air is multiplied by it);
//      ground half: the radiance of a white Lambertian ground lit by the Sun and the sky, seen
//      through the air in front of it (the pixel multiplies it by the surface's reflectance).

bool atm_camera_outside(AtmosphereParams a, float d_m) {
    return d_m > a.top_radius_m;
}

// The horizon's zenith cosine for the table (the camera radius clamped as atm_ray_start does).
float atm_sky_view_horizon_mu(AtmosphereParams a, float d_m) {
    return ray_sphere_horizon_mu(max(d_m, a.bottom_radius_m + 1.0), a.bottom_radius_m);
}

// Row coordinate x in [0, 1] of a ray within its half; `q` is the view zenith cosine (inside; mu_h
// the horizon's) or the impact parameter in metres (outside).
float atm_sky_view_x(AtmosphereParams a, bool outside, float mu_h, bool ground, float q) {
    float R = a.bottom_radius_m;
    if (outside) {
        if (ground) return sqrt(clamp((R - q) / R, 0.0, 1.0));
        float y = clamp((q - R) / (a.top_radius_m - R), 0.0, 1.0);
        return 0.5 - sin(asin(1.0 - 2.0 * y) / 3.0);  // the inverse of y = x^2 (3 - 2 x)
    }
    if (ground) return sqrt(clamp((mu_h - q) / (1.0 + mu_h), 0.0, 1.0));
    return sqrt(clamp((q - mu_h) / (1.0 - mu_h), 0.0, 1.0));
}

// The inverse: q of a row coordinate.
float atm_sky_view_q(AtmosphereParams a, bool outside, float mu_h, bool ground, float x) {
    float R = a.bottom_radius_m;
    if (outside) {
        if (ground) return R * (1.0 - x * x);
        return R + (a.top_radius_m - R) * x * x * (3.0 - 2.0 * x);
    }
    if (ground) return mu_h - (1.0 + mu_h) * x * x;
    return mu_h + (1.0 - mu_h) * x * x;
}

// Table coordinates of a ray: its half, row coordinate x and the cosine of its azimuth from the Sun.
vec2 atm_sky_view_uv(bool ground, float x, float cos_phi, vec2 size) {
    float w = atm_texcoord_from_unit(clamp(x, 0.0, 1.0), 0.5 * size.y);
    float v = ground ? 0.5 * (1.0 - w) : 0.5 * (1.0 + w);
    float half_angle_sin = sqrt(clamp(0.5 - 0.5 * cos_phi, 0.0, 1.0));  // sin(phi / 2)
    return vec2(atm_texcoord_from_unit(half_angle_sin, size.x), v);
}

// The ray of a table coordinate, in the table's frame: the camera on the +z axis at d_m (so the
// centre is along c_hat = -z), the Sun in the x-z plane at zenith cosine mu_s. Returns the unit
// view direction.
vec3 atm_sky_view_direction(AtmosphereParams a, float d_m, vec2 uv, vec2 size) {
    bool ground = uv.y < 0.5;
    bool outside = atm_camera_outside(a, d_m);
    float w = ground ? 1.0 - 2.0 * uv.y : 2.0 * uv.y - 1.0;
    float x = clamp(atm_unit_from_texcoord(w, 0.5 * size.y), 0.0, 1.0);
    float s_half = clamp(atm_unit_from_texcoord(uv.x, size.x), 0.0, 1.0);  // sin(phi / 2)
    float cos_phi = 1.0 - 2.0 * s_half * s_half;
    float sin_phi = 2.0 * s_half * sqrt(max(1.0 - s_half * s_half, 0.0));
    float q = atm_sky_view_q(a, outside, atm_sky_view_horizon_mu(a, d_m), ground, x);
    float sin_t;
    float cos_t;
    if (outside) {  // zenith angle pi - asin(rho / d)
        sin_t = clamp(q / d_m, 0.0, 1.0);
        cos_t = -sqrt((1.0 - sin_t) * (1.0 + sin_t));
    } else {
        cos_t = clamp(q, -1.0, 1.0);
        sin_t = sqrt(max((1.0 - cos_t) * (1.0 + cos_t), 0.0));
    }
    return vec3(sin_t * cos_phi, sin_t * sin_phi, cos_t);
}

vec3 atm_sky_view_sun(float mu_s) {
    return vec3(sqrt(max(1.0 - mu_s * mu_s, 0.0)), 0.0, mu_s);
}

// Linear sRGB of a per-unit-irradiance spectrum given at the sample wavelengths.
vec3 atm_samples_to_rgb(vec3 f, sampler2D weights, float n) {
    return xyz_to_linear_srgb(atm_samples_to_xyz(f, weights, n));
}

// The parts of one texel at one triplet's sample wavelengths: the march along its ray (`samples`
// steps, no shadows). A ray that misses the atmosphere has no in-scatter, transmittance 1 (sky)
// and no ground radiance (ground).
AtmosphereSkyViewSamples atm_sky_view_samples(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms,
                                              vec2 ms_size, sampler2D irr, vec2 irr_size, float d_m, float mu_s,
                                              vec2 uv, vec2 size, int samples) {
    vec3 v = atm_sky_view_direction(a, d_m, uv, size);
    vec3 sun = atm_sky_view_sun(mu_s);
    AtmosphereRayStart st = atm_ray_start(a, d_m, v, vec3(0.0, 0.0, -1.0), sun);
    AtmosphereSkyViewSamples t;
    t.phased = vec3(0.0);
    t.mie = vec3(0.0);
    t.third = vec3(1.0);
    bool ground = uv.y < 0.5;
    if (!st.valid) {
        if (ground) t.third = vec3(0.0);
        return t;
    }
    // The half decides whether the ray ends on the ground, not the rounding of its (r, mu): the
    // horizon row's ray is tangent to the ground in exact arithmetic.
    float t_end = ground ? atm_distance_to_ground(a, st.r_m, st.mu) : atm_distance_to_top(a, st.r_m, st.mu);
    AtmosphereSplitSegment s = atm_march_split(a, trans, trans_size, ms, ms_size, true, st.r_m, st.mu, st.mu_s, st.nu,
                                               t_end, samples,
                                               eclipse_ray(eclipse_no_casters(), vec2(1.0), vec3(0.0), vec3(0.0)), trans);
    t.phased = s.rayleigh_unphased * atm_rayleigh_phase(st.nu) + s.multiple_per_sr;
    t.mie = s.mie_unphased;
    t.third = s.transmittance;
    if (ground) {
        float len = atm_distance_to_ground(a, st.r_m, st.mu);
        float mu_s_g = atm_mu_s_at(st.r_m, st.mu_s, st.nu, len, max(atm_radius_at(st.r_m, st.mu, len), a.bottom_radius_m));
        vec3 e = atm_surface_illuminance(a, trans, trans_size, irr, irr_size, a.bottom_radius_m, mu_s_g);
        t.third = s.transmittance * e * (1.0 / CUPOLA_PI);
    }
    return t;
}

// One texel of the table from one triplet (three sample wavelengths): t[0..2] as in the header.
AtmosphereSkyViewTexel atm_compute_sky_view(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms,
                                            vec2 ms_size, sampler2D irr, vec2 irr_size, sampler2D weights,
                                            float n_weights, float d_m, float mu_s, vec2 uv, vec2 size,
                                            int samples) {
    AtmosphereSkyViewSamples s =
        atm_sky_view_samples(a, trans, trans_size, ms, ms_size, irr, irr_size, d_m, mu_s, uv, size, samples);
    AtmosphereSkyViewTexel t;
    t.phased = atm_samples_to_rgb(s.phased, weights, n_weights);
    t.mie = atm_samples_to_rgb(s.mie, weights, n_weights);
    t.third = atm_samples_to_rgb(s.third, weights, n_weights);
    // A transmittance is never negative, though a deep-red one lies outside the sRGB gamut.
    if (uv.y >= 0.5) t.third = max(t.third / max(atm_samples_to_rgb(vec3(1.0), weights, n_weights), vec3(1e-30)), vec3(0.0));
    return t;
}

// Linear sRGB of a spectrum given at six sample wavelengths (atm_samples6_to_xyz).
vec3 atm_samples6_to_rgb(vec3 f, vec3 f2, sampler2D weights, float n) {
    return xyz_to_linear_srgb(atm_samples6_to_xyz(f, f2, weights, n));
}

// One texel from two triplets: `a` (680/550/440 nm) with its tables and `a2` (610/500/400 nm,
// atmosphere_color.glsl) with its own; the same rays marched at both, each part's spectrum
// rebuilt from the six samples. Twice the march of atm_compute_sky_view; the look-up is the same.
AtmosphereSkyViewTexel atm_compute_sky_view6(AtmosphereParams a, sampler2D trans, vec2 trans_size, sampler2D ms,
                                             vec2 ms_size, sampler2D irr, vec2 irr_size, AtmosphereParams a2,
                                             sampler2D trans2, sampler2D ms2, sampler2D irr2, sampler2D weights,
                                             float n_weights, float d_m, float mu_s, vec2 uv, vec2 size,
                                             int samples) {
    AtmosphereSkyViewSamples s =
        atm_sky_view_samples(a, trans, trans_size, ms, ms_size, irr, irr_size, d_m, mu_s, uv, size, samples);
    AtmosphereSkyViewSamples s2 =
        atm_sky_view_samples(a2, trans2, trans_size, ms2, ms_size, irr2, irr_size, d_m, mu_s, uv, size, samples);
    AtmosphereSkyViewTexel t;
    t.phased = atm_samples6_to_rgb(s.phased, s2.phased, weights, n_weights);
    t.mie = atm_samples6_to_rgb(s.mie, s2.mie, weights, n_weights);
    t.third = atm_samples6_to_rgb(s.third, s2.third, weights, n_weights);
    if (uv.y >= 0.5)
        t.third = max(t.third / max(atm_samples6_to_rgb(vec3(1.0), vec3(1.0), weights, n_weights), vec3(1e-30)), vec3(0.0));
    return t;
}

// The cosine of a view's azimuth from the Sun about the zenith; sin_t is the sine of the view's
// angle from the zenith axis, sun_perp the unit component of the Sun direction perpendicular to
// that axis (0 with the Sun at the zenith or nadir: any azimuth, the table's are all alike then).
float atm_sky_view_cos_phi(vec3 v, float sin_t, vec3 sun_perp) {
    return sin_t > 1e-7 ? clamp(dot(v, sun_perp) / sin_t, -1.0, 1.0) : 1.0;
}

// The unit component of `sun` perpendicular to `up` (or 0), for atm_sky_view_cos_phi.
vec3 atm_sky_view_sun_perp(vec3 up, vec3 sun) {
    vec3 p = sun - up * dot(sun, up);
    float l = length(p);
    return l > 1e-7 ? p / l : vec3(0.0);
}

// Table coordinates of a ray from a camera inside the atmosphere (up: unit, centre -> camera;
// mu_h: the horizon's zenith cosine; sun_perp: atm_sky_view_sun_perp(up, sun)), given its
// ground flag: cosines and square roots only.
vec2 atm_sky_view_inside_uv(AtmosphereParams a, vec3 v, vec3 up, float mu_h, vec3 sun_perp, bool ground, vec2 size) {
    float mu = dot(v, up);
    float x = atm_sky_view_x(a, false, mu_h, ground, mu);
    float sin_t = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
    return atm_sky_view_uv(ground, x, atm_sky_view_cos_phi(v, sin_t, sun_perp), size);
}

// Whether the ground hides what lies beyond the air along v (a camera inside the atmosphere).
bool atm_sky_in_front_hidden(AtmosphereParams a, SkyInFront s, vec3 v) {
    return atm_ray_hits_ground(a, s.r_m, dot(v, s.up));
}

// The table coordinates of the air in front of what lies beyond it along v (not hidden): its
// in-scatter is atm_sky_view_inscatter there with nu = dot(v, s.sun), its transmittance part 2.
vec2 atm_sky_in_front_uv(AtmosphereParams a, SkyInFront s, vec3 v) {
    return atm_sky_view_inside_uv(a, v, s.up, s.mu_h, s.sun_perp, false, s.size);
}

// What a pixel needs to look its ray up, in general (inside or outside): the half, the row
// coordinate and the azimuth. `st` is the ray's start (atm_ray_start with the same d_m, v, c_hat,
// sun), `ground` its ground flag.
vec2 atm_sky_view_pixel_uv(AtmosphereParams a, float d_m, vec3 v, vec3 c_hat, vec3 sun, AtmosphereRayStart st,
                           bool ground, vec2 size) {
    vec3 up = -c_hat;
    bool outside = atm_camera_outside(a, d_m);
    // |v x up| = sin(angle(v, up)), free of cancellation for small angles (outside, far away);
    // outside, rho = d |v x up|.
    float sin_t = length(cross(v, up));
    float q = outside ? d_m * sin_t : st.mu;
    float x = atm_sky_view_x(a, outside, atm_sky_view_horizon_mu(a, d_m), ground, q);
    return atm_sky_view_uv(ground, x, atm_sky_view_cos_phi(v, sin_t, atm_sky_view_sun_perp(up, sun)), size);
}

// The pixel's light from the table: the in-scatter (linear sRGB per unit solar irradiance, the
// Mie phase of the pixel's own nu applied) and, in `third`, the transmittance (sky) or the white
// ground's radiance (ground) of texel part 2.
vec3 atm_sky_view_inscatter(AtmosphereParams a, sampler2D t0, sampler2D t1, vec2 uv, float nu) {
    return vec3(textureLod(t0, uv, 0.0)) + vec3(textureLod(t1, uv, 0.0)) * atm_cornette_shanks_phase(a.mie_g, nu);
}

// The air's own light in front of what lies beyond it along v (not hidden), in scene units: the
// Sun's in-scatter from its table (parts t0, t1) and, with a moonlit sky (s.moon_scale not 0), the
// Moon's from its own table (m0, m1) at its own azimuth and phase angle.
vec3 atm_sky_in_front_inscatter(AtmosphereParams a, SkyInFront s, sampler2D t0, sampler2D t1, sampler2D m0,
                                sampler2D m1, vec3 v) {
    vec2 uv = atm_sky_in_front_uv(a, s, v);
    vec3 light = max(atm_sky_view_inscatter(a, t0, t1, uv, dot(v, s.sun)), vec3(0.0)) * s.solar_scale;
    if (s.moon_scale.x + s.moon_scale.y + s.moon_scale.z > 0.0) {
        vec2 moon_uv = atm_sky_view_inside_uv(a, v, s.up, s.mu_h, s.moon_perp, false, s.size);
        light = light + max(atm_sky_view_inscatter(a, m0, m1, moon_uv, dot(v, s.moon)), vec3(0.0)) * s.moon_scale;
    }
    return light;
}

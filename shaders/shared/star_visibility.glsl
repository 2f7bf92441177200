// Whether the eye can see a star against the sky behind it (shared by GLSL and C++).
//
// The threshold is Schaefer's (Schaefer 1990, section II, equations 2 and 3, from the laboratory
// data of Hecht 1947 and Knoll, Tousey & Hulburt 1946): a point source is seen when its
// illuminance at the eye exceeds
//   I = C1 (1 + sqrt(C2 B))^2 foot-candles, B the background's luminance in nanolamberts,
// with C1 = 10^-9.8, C2 = 10^-1.9 for the dark-adapted eye (rods, B below 10^3.17 nL) and
// C1 = 10^-8.35, C2 = 10^-5.9 above it (cones). A star of visual magnitude m gives
// 10^(-0.4 (m + 16.57)) foot-candles, so the faintest visible magnitude is
//   m_lim = -16.57 - 2.5 log10(C1) - 5 log10(1 + sqrt(C2 B)):
// 7.93 on a black background, 6.6 under a dark sky of 22 mag/arcsec^2, about -4 by day.
// The star's own magnitude is dimmed by the air in front of it (its luminance transmittance).
// Nothing here depends on a channel: the sky is the sky-view table's, which every channel renders
// alike, and the direction is the star's in the world, so a star is seen or not on every channel.

const float STAR_NANOLAMBERT_PER_CD_M2 = 3.14159265e5;  // 1 cd/m^2 = pi x 10^-4 lambert
const float STAR_RODS_BELOW_NL = 1479.1;                // 10^3.17
const float STAR_LOG10_2 = 0.30102999566;
// A star fades in over this many magnitudes above the threshold instead of popping in as the
// sky darkens; one exactly at the threshold has weight 0.
const float STAR_FADE_MAG = 0.5;

// The faintest visual magnitude the eye sees against a background of this luminance (cd/m^2).
float eye_limiting_magnitude(float background_cd_m2) {
    float b_nl = max(background_cd_m2, 0.0) * STAR_NANOLAMBERT_PER_CD_M2;
    bool rods = b_nl < STAR_RODS_BELOW_NL;
    float c2 = rods ? 1.2589254e-2 : 1.2589254e-6;      // 10^-1.9, 10^-5.9
    float offset = rods ? 7.93 : 4.305;                  // -16.57 - 2.5 log10(C1)
    return offset - 5.0 * STAR_LOG10_2 * log2(1.0 + sqrt(c2 * b_nl));
}

// The air in front of a star and the sky behind it, from the sky-view table (parts t0, t1, t2 of
// shared/atmosphere_sky_view.glsl) of the atmosphere around c_hat: v, c_hat (camera -> planet
// centre) and sun (planet centre -> Sun) are unit vectors in one frame, d_m the camera's distance
// from the centre. Returns (rgb: the transmittance in front of the star per sRGB channel, what the
// atmosphere's look-up multiplies what lies beyond the air by; w: the sky's luminance behind the
// star per unit solar irradiance); w < 0 and rgb 1 where the ray misses the air, rgb 0 where it
// meets the ground.
vec4 star_sky_light(AtmosphereParams a, sampler2D t0, sampler2D t1, sampler2D t2, vec2 size, float d_m, vec3 v,
                    vec3 c_hat, vec3 sun) {
    AtmosphereRayStart st = atm_ray_start(a, d_m, v, c_hat, sun);
    if (!st.valid) return vec4(1.0, 1.0, 1.0, -1.0);
    if (atm_ray_hits_ground(a, st.r_m, st.mu)) return vec4(0.0);
    vec2 uv = atm_sky_view_pixel_uv(a, d_m, v, c_hat, sun, st, false, size);
    vec3 sky = max(atm_sky_view_inscatter(a, t0, t1, uv, st.nu), vec3(0.0));
    return vec4(vec3(textureLod(t2, uv, 0.0)), rec709_luminance(sky));
}

// What the eye's threshold takes of star_sky_light: (the sky's luminance behind the star, the
// luminance transmittance in front of it); x < 0 where the ray misses the air.
vec2 star_sky_behind_of(vec4 light) {
    if (light.w < 0.0) return vec2(-1.0, 1.0);
    return vec2(light.w, max(rec709_luminance(vec3(light)), 0.0));
}

// The same from the table directly.
vec2 star_sky_behind(AtmosphereParams a, sampler2D t0, sampler2D t1, sampler2D t2, vec2 size, float d_m, vec3 v,
                     vec3 c_hat, vec3 sun) {
    return star_sky_behind_of(star_sky_light(a, t0, t1, t2, size, d_m, v, c_hat, sun));
}

// How much of a star of visual magnitude v_mag shows, 0 to 1, given star_sky_behind's `behind`
// and the factor that turns its luminance into cd/m^2: 1 where there is no air, 0 behind the
// ground or below the threshold, rising to 1 over STAR_FADE_MAG above it.
// glow_cd_m2: the night sky's own light behind the star (shared/night_sky.glsl), added to the
// scattered sunlight and moonlight.
float star_sky_weight_over(vec2 behind, float to_cd_m2, float glow_cd_m2, float v_mag) {
    if (behind.x < 0.0) return 1.0;
    if (behind.y <= 0.0) return 0.0;
    float seen_mag = v_mag - 2.5 * STAR_LOG10_2 * log2(behind.y);
    float limit_mag = eye_limiting_magnitude(behind.x * to_cd_m2 + glow_cd_m2);
    return clamp((limit_mag - seen_mag) / STAR_FADE_MAG, 0.0, 1.0);
}

float star_sky_weight(vec2 behind, float to_cd_m2, float v_mag) {
    return star_sky_weight_over(behind, to_cd_m2, 0.0, v_mag);
}

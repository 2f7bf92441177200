#version 450 core
// Limb-darkened stellar disc and its corona. The view ray meets the sphere analytically; mu
// gives the darkening. Around the disc, out to CORONA_EXTENT solar radii, the corona: Baumbach's
// mean brightness profile (Allen's Astrophysical Quantities), relative to the disc's mean
// radiance,
//   B(rho) / B_disc = 1e-6 (0.0532 rho^-2.5 + 1.425 rho^-7 + 2.565 rho^-17),  rho in radii,
// times the scene's `corona` factor. It is always drawn (added over the stars behind it); about
// a millionth of the disc, it shows only once the Moon covers the disc and the atmosphere's
// in-scatter falls with the visible fraction, i.e. in totality.
// The disc also writes the deferred geometry (no diffuse reflectance, hit distance in metres) so
// that an atmosphere behind the disc leaves it alone; the corona leaves "background". Drawn
// additively (alpha 0: the colour's coverage stays 1). SUN_AFTER_SKY: the sky was drawn first
// (FrameContext::sky_first), and the disc and the corona take the air in front of them here.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_center_dir;     // unit, channel frame
uniform float u_sin_alpha;     // of the billboard's sphere (the corona's extent)
uniform vec4 u_distances_m;    // of the billboard's sphere (unused)
uniform float u_disc_sin_alpha;  // R / d of the disc itself
uniform vec4 u_disc_distances_m; // (d, R, d - R, d + R) of the disc in metres, from the CPU in double
uniform vec3 u_radiance;       // disc-centre radiance times tint
uniform float u_limb_u;
uniform float u_corona;        // 0: no corona
uniform int u_limb_aa;         // 1: a small disc (PlanetLight::small_disc), its limb antialiased
uniform float u_disc_weight;   // the disc's share of the light (the rest is a point); not the corona's
#if SUN_AFTER_SKY
uniform AtmosphereParams u_atm;  // the air in front (SkyInFront: slave/passes/beyond_the_air.hpp)
uniform SkyInFront u_sky;
uniform sampler2D u_sky_third;
#endif

layout(location = 0) out vec4 frag_color;
#if !SUN_AFTER_SKY
layout(location = 1) out vec4 frag_geometry;
#endif

// What the disc or the corona adds here: as it is, or (SUN_AFTER_SKY, the sky drawn first) times
// the air's transmittance in front of it, as the atmosphere's look-up would have multiplied it;
// nothing below the horizon. Alpha 0: the coverage stays what it was.
vec4 added(vec3 v, vec3 radiance) {
#if SUN_AFTER_SKY
    if (atm_sky_in_front_hidden(u_atm, u_sky, v)) discard;
    radiance *= vec3(textureLod(u_sky_third, atm_sky_in_front_uv(u_atm, u_sky, v), 0.0));
#endif
    return vec4(radiance, 0.0);
}

const float CORONA_EXTENT = 6.0;

float corona_profile(float rho) {
    return 1e-6 * (0.0532 * pow(rho, -2.5) + 1.425 * pow(rho, -7.0) + 2.565 * pow(rho, -17.0));
}

// A small disc's limb pixel: its coverage by the disc (from how far its centre lies inside the
// limb, rho = 1, in units of rho's change across the pixel) and mu in the middle of the covered
// part, so that a disc a few pixels across keeps its light (as body.frag does for the planets).
vec2 small_disc_coverage_mu(float rho, float rho_step) {
    float coverage = clamp((1.0 - rho) / max(rho_step, 1e-6) + 0.5, 0.0, 1.0);
    float rho_shaded = min(rho, 1.0 - 0.5 * coverage * rho_step);
    return vec2(coverage, sqrt(max(1.0 - rho_shaded * rho_shaded, 0.0)));
}

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    float theta = angle_between_units(v, u_center_dir);
    float rho = sin(min(theta, 1.5707963)) / u_disc_sin_alpha;
    float rho_step = fwidth(rho);  // in uniform control flow
    vec4 hit = sphere_hit(v, u_center_dir, u_disc_sin_alpha);
    vec2 cover = u_limb_aa == 0 ? vec2(hit.w >= 0.0 ? 1.0 : 0.0, hit.w) : small_disc_coverage_mu(rho, rho_step);
    if (cover.x > 0.0) {
        frag_color = added(v, cover.x * u_disc_weight * u_radiance * limb_darkening(cover.y, u_limb_u));
#if !SUN_AFTER_SKY
        float mu_hit = max(hit.w, 0.0);  // a limb pixel whose centre misses: the distance at the limb
        frag_geometry = vec4(0.0, 0.0, 0.0, sphere_hit_distance(v, u_center_dir, mu_hit, u_disc_distances_m));
#endif
        return;
    }
    if (u_corona <= 0.0 || theta >= 1.5707963 || rho >= CORONA_EXTENT) {
        discard;
    }
    vec3 mean_disc = u_radiance * limb_darkening_disc_average(u_limb_u);
    frag_color = added(v, mean_disc * (u_corona * corona_profile(max(rho, 1.0))));
#if !SUN_AFTER_SKY
    frag_geometry = vec4(0.0, 0.0, 0.0, -1.0);
#endif
}

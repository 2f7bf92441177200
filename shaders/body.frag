#version 450 core
// A planet or moon: analytic ray-sphere hit, equirectangular texture in the body frame
// (lon = atan(y, x), north = +Z), lit by the sun through its surface's photometric function
// (Lambert or lunar-Lambert, shared/surface_photometry.glsl) and by the body it circles
// (earthshine). Also writes the deferred geometry the atmosphere pass reads: diffuse reflectance (linear) and the hit distance in metres, and a
// logarithmic depth of that distance for the glare probe's occlusion queries.
// BODY_RINGS: a ringed planet, darkened where its rings shade it from the Sun (ring_shadow).
// Eclipse shadows: the sunlight at the surface point (normal * radius, relative to the centre,
// like the casters in u_ecl) is scaled by eclipse_light (shaders/shared/eclipse_casters.glsl),
// only in the BODY_ECLIPSE variant (slave/passes/body_pass.cpp): on a CPU rasteriser a branch
// costs whether taken or not, and a body whose atmosphere relights its surface needs none.
// BODY_AFTER_SKY: the sky was drawn first (FrameContext::sky_first); the body is composed with the
// air in front of it here and writes no geometry.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_center_dir;       // unit, channel frame
uniform float u_sin_alpha;       // R / d
uniform vec4 u_distances_m;      // (d, R, d - R, d + R) in metres, from the CPU in double
uniform mat3 u_channel_to_body;
#if BODY_OBLATE
uniform mat3 u_to_sphere;        // channel frame -> stretched frame (symmetric)
uniform mat3 u_from_sphere;      // its inverse
#endif
uniform vec3 u_sun_dir;          // unit, channel frame, from the body towards the sun
uniform vec3 u_lit;              // albedo / pi * irradiance * tint
uniform vec3 u_reflectance;      // albedo * tint
uniform sampler2D u_texture;     // linear RGB, row 0 = north, mipmapped
uniform float u_limb_weight;     // lunar-Lambert L at the Sun's phase (0: Lambert), surface_photometry.glsl
uniform vec3 u_shine_dir;        // unit, channel frame, toward the body this one circles (earthshine)
uniform vec3 u_shine_lit;        // its light, as u_lit has the Sun's (0: none)
uniform float u_shine_limb_weight;
uniform int u_limb_aa;           // 1: a small disc, its limb antialiased (PlanetLight::small_disc)
uniform float u_map_lod;         // the map level a pixel spans at the disc's centre (from the CPU)
uniform EclipseCasters u_ecl;    // channel frame, metres from the body's centre
uniform sampler2D u_eclipse_lut;
uniform vec2 u_eclipse_lut_size;
#if BODY_RINGS
uniform vec3 u_ring_normal;        // unit, channel frame: the planet's pole
uniform sampler2D u_ring_profile;  // the rings' normal optical depth by radius (passes/ring_profile)
uniform vec2 u_ring_profile_map;   // s = r * x + y, r in planet radii
#endif
#if BODY_AFTER_SKY
uniform AtmosphereParams u_atm;  // the air in front (SkyInFront: slave/passes/beyond_the_air.hpp)
uniform SkyInFront u_sky;
uniform sampler2D u_sky_phased;
uniform sampler2D u_sky_mie;
uniform sampler2D u_sky_third;
uniform sampler2D u_sky_moon_phased;  // the Moon's table, with a moonlit sky (u_sky.moon_scale)
uniform sampler2D u_sky_moon_mie;
uniform int u_halo_on;     // the sky's draw added the glare's halo: so does this one
uniform sampler2D u_halo;  // as atmosphere_lookup.frag has them
uniform vec4 u_halo_map;
#endif

layout(location = 0) out vec4 frag_color;
#if !BODY_AFTER_SKY
layout(location = 1) out vec4 frag_geometry;  // (reflectance, distance)
#endif

#if BODY_AFTER_SKY
// The sky was drawn first: the body replaces it, seen through the air in front as the
// atmosphere's look-up composes what lies beyond the air (times the transmittance, plus the
// in-scatter), with the glare's halo the sky's draw added. Below the horizon the ground is in front.
vec4 through_the_air(vec3 v, vec3 radiance) {
    if (atm_sky_in_front_hidden(u_atm, u_sky, v)) discard;
    vec2 uv = atm_sky_in_front_uv(u_atm, u_sky, v);
    vec3 c = radiance * vec3(textureLod(u_sky_third, uv, 0.0)) +
             atm_sky_in_front_inscatter(u_atm, u_sky, u_sky_phased, u_sky_mie, u_sky_moon_phased, u_sky_moon_mie, v);
    if (u_halo_on != 0) c += textureLod(u_halo, gl_FragCoord.xy * u_halo_map.xy + u_halo_map.zw, 0.0).rgb;
    return vec4(c, 1.0);
}
#endif

#if BODY_RINGS
// The sunlight the rings let through to a point of the surface (planet radii from the centre):
// where the ray to the Sun crosses the ring plane, the slab's transmission along it. The Sun's
// own size is left out: at Saturn it blurs a ring edge's shadow by under 60 km, a third of a texel
// of the ring map.
float ring_shadow(vec3 surface, vec3 sun) {
    float t = ring_plane_hit(surface, sun, u_ring_normal);
    if (t <= 0.0) return 1.0;
    float s = length(surface + t * sun) * u_ring_profile_map.x + u_ring_profile_map.y;
    if (s < 0.0 || s > 1.0) return 1.0;
    float tau = textureLod(u_ring_profile, vec2(s, 0.5), 0.0).r;
    return ring_transmission(tau, abs(dot(sun, u_ring_normal)));
}
#endif

// The pixel's coverage by the disc, from how far its centre lies inside the limb (rho = 1) in units
// of rho's change across the pixel; the hit of a centre just outside is taken on the limb.
float limb_coverage(float rho) {
    if (u_limb_aa == 0) return rho < 1.0 ? 1.0 : 0.0;
    return clamp((1.0 - rho) / max(fwidth(rho), 1e-6) + 0.5, 0.0, 1.0);
}

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
#if BODY_OBLATE
    vec3 vs = u_to_sphere * v;
    float stretch = length(vs);
    vs /= stretch;
#else
    vec3 vs = v;
#endif
    float rho = sphere_limb_rho(vs, u_center_dir, u_sin_alpha);
    float coverage = limb_coverage(rho);
    if (coverage <= 0.0) {
        discard;
    }
    // A pixel across the limb is shaded at the middle of its covered part, not on the limb itself
    // (where cos i falls to 0), so that a small disc keeps its light.
    float rho_shaded = u_limb_aa == 0 ? rho : min(rho, 1.0 - 0.5 * coverage * fwidth(rho));
    float sin_alpha = u_sin_alpha;
    if (u_limb_aa != 0) sin_alpha *= rho_shaded < 0.9999 ? rho / max(rho_shaded, 1e-6) : rho * 1.0001;
    vec4 hit = sphere_hit(vs, u_center_dir, sin_alpha);
    if (hit.w < 0.0) {
        discard;
    }
#if BODY_OBLATE
    vec3 n = normalize(u_to_sphere * hit.xyz);
    vec3 surface = u_from_sphere * hit.xyz;  // the hit point / R, from the centre
#else
    vec3 n = hit.xyz;
    vec3 surface = n;
#endif
    vec3 albedo_map = textureLod(u_texture, body_map_uv(u_channel_to_body, n), u_map_lod).rgb;
    float cos_e = max(-dot(n, v), 0.0);
    float cos_i = max(dot(n, u_sun_dir), 0.0);
    float sunlit = lunar_lambert(cos_i, cos_e, u_limb_weight);
    vec3 light = vec3(1.0);
#if BODY_ECLIPSE
    if (u_ecl.count > 0 && cos_i > 0.0) {
        light = eclipse_light(u_ecl, u_eclipse_lut, u_eclipse_lut_size, surface * u_distances_m.y);
    }
#endif
#if BODY_RINGS
    if (cos_i > 0.0) light *= ring_shadow(surface, u_sun_dir);
#endif
    vec3 shine = u_shine_lit * lunar_lambert(dot(n, u_shine_dir), cos_e, u_shine_limb_weight);
    vec3 radiance = (u_lit * sunlit * light + shine) * albedo_map;
#if BODY_AFTER_SKY
    frag_color = coverage * through_the_air(v, radiance);
#else
    frag_color = coverage * vec4(radiance, 1.0);
#if BODY_OBLATE
    float distance_m = sphere_hit_distance(vs, u_center_dir, hit.w, u_distances_m) / stretch;
#else
    float distance_m = sphere_hit_distance(vs, u_center_dir, hit.w, u_distances_m);
#endif
    frag_geometry = vec4(u_reflectance * albedo_map, distance_m);
    gl_FragDepth = log_depth(distance_m);  // only a depth target (the glare probe) keeps it
#endif
}

#version 450 core
// A planet's rings (slave/passes/ring_drawer.cpp): the view ray meets the equatorial plane, the
// radius there reads the rings' normal optical depth, and the slab shines from the face the Sun
// lights or glows through from the other (shared/ring_photometry.glsl), less where the planet hides
// the Sun. Whatever lies behind shows through by the slab's transmission: premultiplied colour,
// alpha = 1 - transmission. Where the planet is nearer than the plane along the ray, nothing is
// drawn (the rings' far side behind the globe), but for the part of a limb pixel the globe leaves.
// Lengths in planet radii from its centre, channel frame; the planet is the unit sphere after
// u_to_sphere (its stretched frame). RING_AFTER_SKY:
// the sky was drawn first, and the rings take the air in front of them (through_the_air).
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_camera;          // the camera, relative to the planet's centre
uniform vec3 u_normal;          // the planet's north pole (the rings' normal)
uniform mat3 u_to_sphere;       // channel frame -> stretched frame (identity for a sphere)
uniform vec3 u_sun_dir;         // unit, toward the Sun
uniform float u_sun_radius_rad; // the Sun's angular radius at the planet
uniform sampler2D u_profile;    // (normal optical depth, relative albedo) by radius, one row, mipmapped (passes/ring_profile)
uniform vec2 u_profile_map;     // s = r * x + y
uniform float u_profile_texels;
uniform vec3 u_lit;             // tint * phase_albedo / 4 * E_sun / pi * disc weight (I/F -> radiance, times varpi0 P / 4)
uniform int u_limb_aa;          // 1: the globe is a small disc, its limb antialiased (body.frag's u_limb_aa)
uniform int u_supersample;      // n: n x n rays a pixel (small rings), else 1

#if RING_AFTER_SKY
uniform AtmosphereParams u_atm;  // the air in front (SkyInFront: slave/passes/beyond_the_air.hpp)
uniform SkyInFront u_sky;
uniform sampler2D u_sky_phased;
uniform sampler2D u_sky_mie;
uniform sampler2D u_sky_third;
uniform sampler2D u_sky_moon_phased;  // the Moon's table, with a moonlit sky (u_sky.moon_scale)
uniform sampler2D u_sky_moon_mie;
uniform int u_halo_on;     // the sky's draw added the glare's halo
uniform sampler2D u_halo;  // as atmosphere_lookup.frag has them
uniform vec4 u_halo_map;
#endif

layout(location = 0) out vec4 frag_color;

#if RING_AFTER_SKY
// The sky was drawn first (FrameContext::sky_first): the rings' light comes through the air's
// transmittance, and the air's own light in front of them (in-scatter, the glare's halo), which
// the colour already holds, must not be dimmed by them: it is added back by the part they block.
vec3 through_the_air(vec3 v, vec3 radiance, float blocked) {
    if (atm_sky_in_front_hidden(u_atm, u_sky, v)) discard;
    vec2 uv = atm_sky_in_front_uv(u_atm, u_sky, v);
    vec3 in_front =
        atm_sky_in_front_inscatter(u_atm, u_sky, u_sky_phased, u_sky_mie, u_sky_moon_phased, u_sky_moon_mie, v);
    if (u_halo_on != 0) in_front += textureLod(u_halo, gl_FragCoord.xy * u_halo_map.xy + u_halo_map.zw, 0.0).rgb;
    return radiance * vec3(textureLod(u_sky_third, uv, 0.0)) + blocked * in_front;
}
#endif

// One ray's rings: (radiance, blocked) times the part of the ray the globe leaves; zero where the
// ray misses them. fw_rho: the limb's antialiasing width (body.frag's fwidth(rho)); lod: the
// profile's mip level.
vec4 ring_sample(vec3 v, float fw_rho, float lod) {
    float t = ring_plane_hit(u_camera, v, u_normal);
    if (t <= 0.0) return vec4(0.0);
    // The globe in front: where the ring plane lies beyond the ray's closest approach to the
    // globe's centre, the globe covers the pixel as body.frag's limb covers it (antialiased for a
    // small disc), and the rings show on the rest (the limb of a small globe would otherwise cut
    // them a whole pixel at a time).
    vec3 cs = u_to_sphere * u_camera, vs = u_to_sphere * v;
    float rho = length(cross(cs, vs)) / length(vs);  // the ray's distance from the centre: 1 on the limb
    float globe = u_limb_aa == 0 ? (rho < 1.0 ? 1.0 : 0.0) : clamp((1.0 - rho) / max(fw_rho, 1e-6) + 0.5, 0.0, 1.0);
    float shown = t > -dot(cs, vs) / dot(vs, vs) ? 1.0 - globe : 1.0;
    if (shown <= 0.0) return vec4(0.0);
    vec3 q = u_camera + t * v;
    float s = length(q) * u_profile_map.x + u_profile_map.y;
    if (s < 0.0 || s > 1.0) return vec4(0.0);
    vec2 texel = textureLod(u_profile, vec2(s, 0.5), max(lod, 0.0)).rg;  // (tau, relative albedo)
    float tau = texel.x;
    float mu0 = abs(dot(u_sun_dir, u_normal));
    float mu = abs(dot(v, u_normal));
    bool same_side = (dot(u_camera, u_normal) > 0.0) == (dot(u_sun_dir, u_normal) > 0.0);
    float sunlit = ring_sunlit_fraction(u_to_sphere * q, u_to_sphere * u_sun_dir, u_sun_radius_rad);
    vec3 radiance = u_lit * (texel.y * sunlit * ring_reflectance(tau, mu0, mu, same_side));
    return shown * vec4(radiance, 1.0 - ring_transmission(tau, mu));
}

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    // The footprints, from the pixel's centre ray in uniform control flow (the samples below may
    // miss the rings where the centre does not).
    vec3 cs = u_to_sphere * u_camera, vs = u_to_sphere * v;
    float fw_rho = fwidth(length(cross(cs, vs)) / length(vs));
    float t_c = ring_plane_hit(u_camera, v, u_normal);
    float s_c = length(u_camera + t_c * v) * u_profile_map.x + u_profile_map.y;
    float lod = log2(max(fwidth(s_c) * u_profile_texels, 1e-6));
    if (isnan(lod) || isinf(lod)) lod = 0.0;  // a centre ray along the ring plane
    vec4 ring;
    if (u_supersample > 1) {
        // Small rings (PlanetLight::supersample): the mean of n x n rays over the pixel, whose edges,
        // gaps and globe shadow, finer than a pixel, would otherwise flicker from frame to frame.
        float n = float(u_supersample);
        ring = vec4(0.0);
        for (int j = 0; j < u_supersample; ++j) {
            for (int i = 0; i < u_supersample; ++i) {
                vec3 vi = channel_ray(gl_FragCoord.xy + (vec2(i, j) + 0.5) / n - 0.5, u_size, u_tangents);
                ring += ring_sample(vi, fw_rho / n, lod - log2(n));
            }
        }
        ring /= n * n;
    } else {
        ring = ring_sample(v, fw_rho, lod);
    }
    if (ring.a <= 0.0 && all(lessThanEqual(ring.rgb, vec3(0.0)))) discard;
    vec3 radiance = ring.rgb;
#if RING_AFTER_SKY
    radiance = through_the_air(v, radiance, ring.a);
#endif
    frag_color = vec4(radiance, ring.a);
}

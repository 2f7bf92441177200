#version 450 core
// Deferred atmosphere of one planet from its sky-view table (shaders/shared/atmosphere_sky_view.glsl,
// rendered this frame by sky_view.frag): about one table fetch per pixel instead of a march.
// Blended in place with dual-source blending (slave/passes/atmosphere_pass.cpp):
//   colour = out_add + colour_so_far * out_factor,
// so the pass touches only the pixels of its scissor (the top-of-atmosphere sphere's screen
// bounds) and copies nothing. Where the pixel shows this planet's surface, the surface is relit:
// its reflectance times the table's white-ground radiance (the Sun and the sky on the ground, seen
// through the air in front); elsewhere what lies beyond the air is multiplied by the table's
// transmittance. Scene geometry inside the air (not this planet's surface) is marched per pixel,
// the only pixels that are. Eclipse shadows on this planet draw with the march pass instead
// (atmosphere.frag), except the illustrative mode, which tints the surface only.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_center_dir;   // unit, channel frame: camera -> planet centre
uniform float u_sin_alpha;   // R / d (at most 1), as the body pass had it
uniform vec4 u_distances_m;  // (d, R, d - R, d + R) in metres, as the body pass had them
uniform float u_d_m;         // camera -> planet centre, metres
uniform vec3 u_sun;          // unit, channel frame: planet centre -> Sun
uniform float u_solar_scale; // scene irradiance of the Sun / illuminance of the physical spectrum
uniform AtmosphereParams u_atm;
uniform int u_samples;       // march steps for geometry inside the air
uniform vec2 u_trans_size;
uniform vec2 u_ms_size;
uniform vec2 u_irr_size;
uniform float u_weight_count;
uniform sampler2D u_geometry;  // (reflectance, distance); distance < 0: nothing drawn
uniform sampler2D u_transmittance;
uniform sampler2D u_multiple_scattering;
uniform sampler2D u_irradiance;
uniform sampler2D u_weights;
uniform sampler2D u_sky_phased;
uniform sampler2D u_sky_mie;
uniform sampler2D u_sky_third;
uniform vec2 u_sky_size;
uniform float u_mu_h;        // the ground horizon's zenith cosine at the camera (inside)
uniform vec3 u_sun_perp;     // atm_sky_view_sun_perp(-u_center_dir, u_sun)
uniform EclipseCasters u_ecl;  // illustrative mode only (or none)
uniform sampler2D u_eclipse_lut;
uniform vec2 u_eclipse_lut_size;
uniform sampler2D u_halo;  // SKY_HALO: the glare's halo target (slave/passes/glare_halo_pass.hpp)
uniform vec4 u_halo_map;   // its texture coordinate = gl_FragCoord.xy * u_halo_map.xy + u_halo_map.zw
uniform sampler2D u_body_map;   // SKY_HALF 2: the planet's map (linear RGB), as the body pass has it
uniform mat3 u_channel_to_body;
uniform vec3 u_reflectance;     // albedo * tint
uniform float u_map_lod;        // the map's level, as the body pass samples it (BodyPass::map_lod)
uniform sampler2D u_moon_phased;  // SKY_MOON: the Moon's sky-view table (common/atmosphere/moonlit_sky.hpp)
uniform sampler2D u_moon_mie;
uniform sampler2D u_moon_third;
uniform vec3 u_moon;            // unit, channel frame: camera -> Moon
uniform vec3 u_moon_perp;       // atm_sky_view_sun_perp(-u_center_dir, u_moon)
uniform vec3 u_moon_scale;      // the Moon's irradiance over the Sun's, per channel, times u_solar_scale
uniform float u_disc_weight;    // the planet's disc weight from point to disc (passes/planet_light): 0..1
uniform vec3 u_night_sky;      // the night sky's own glow at the zenith, scene units (shared/night_sky.glsl)
uniform int u_supersample;      // SKY_OUTSIDE and SKY_MAP: n x n rays a pixel (a small disc: PlanetLight::supersample)

layout(location = 0, index = 0) out vec4 out_add;
layout(location = 0, index = 1) out vec4 out_factor;

void keep_scene() {
    out_add = vec4(0.0);
    out_factor = vec4(1.0);
}

#if SKY_GEOMETRY
// Geometry inside the air: the march up to it (the table holds whole rays only).
void march_to_geometry(AtmosphereRayStart st, float g) {
    AtmosphereSegment seg = atm_view_ray(u_atm, u_transmittance, u_trans_size, u_multiple_scattering, u_ms_size,
                                         true, st, g, u_samples);
    out_add = vec4(max(atm_samples_to_rgb(seg.inscatter_per_sr, u_weights, u_weight_count), vec3(0.0)) * u_solar_scale, 0.0);
    out_factor = vec4(atm_samples_to_rgb(seg.transmittance, u_weights, u_weight_count) /
                      max(atm_samples_to_rgb(vec3(1.0), u_weights, u_weight_count), vec3(1e-30)), 1.0);
}
#endif

// The variants (defined in the prelude by slave/passes/atmosphere_pass.cpp, each 0 or 1): on a
// CPU rasteriser such as llvmpipe both sides of a branch cost, taken or not, so what a frame does
// not need is compiled out rather than branched around.
//   SKY_OUTSIDE       the camera is above the top of the atmosphere
//   SKY_GEOMETRY      another body is inside the shell: pixels showing it march up to it
//   SKY_ILLUSTRATIVE  illustrative eclipse shadows tint the surface
//   SKY_HALO          the glare's halo is added here, not by a full-screen draw of its own
//   SKY_HALF          0 every pixel; 1 the sky only, 2 the ground only (inside, without
//                     SKY_GEOMETRY): the draw is split in two by the ray's ground flag, each half
//                     over its own cap and discarding the other's pixels, and each free of the
//                     other's branch. In the ground half the body pass did not draw the planet:
//                     the reflectance comes from its map here, not from the G-buffer
//   SKY_FIRST         (with SKY_HALF) the sky is drawn first and written, not blended, over a
//                     colour that was never cleared: the stars, the Sun and the bodies beyond
//                     the air are drawn after it, each taking the air in front of it from the
//                     table itself (slave/passes/beyond_the_air.hpp), so the sky needs no
//                     transmittance
//   SKY_MAP           (outside) the draw relights the planet's surface itself, from its map, as
//                     the ground half does inside: nothing else is in front of the air
//   SKY_MOON          (inside) the Moon lights the air and the ground too, from its own table
//   SKY_TERRAIN       (with SKY_GEOMETRY) the planet is drawn as relief (terrain.frag lit it):
//                     every pixel with geometry is marched up to it, none relit as a sphere

// The Moon's light along the ray (scene units; a camera inside the air): the in-scatter from its
// own table at its own azimuth and phase angle, and where the ray meets the ground the ground lit
// by it (the table's part 2 there) times the surface's reflectance.
vec3 moonlight(vec3 v, bool ground, vec3 reflectance) {
#if SKY_MOON
    vec2 uv = atm_sky_view_inside_uv(u_atm, v, -u_center_dir, u_mu_h, u_moon_perp, ground, u_sky_size);
    vec3 light = atm_sky_view_inscatter(u_atm, u_moon_phased, u_moon_mie, uv, dot(v, u_moon));
    if (ground) light += reflectance * vec3(textureLod(u_moon_third, uv, 0.0));
    return max(light, vec3(0.0)) * u_moon_scale;
#else
    return vec3(0.0);
#endif
}

// The pixel's light from the table at uv: through the air (sky) or on the ground (relit surface).
void from_table(vec2 uv, float nu, bool ground, bool surface, vec4 geo, vec3 v) {
    vec3 inscatter = atm_sky_view_inscatter(u_atm, u_sky_phased, u_sky_mie, uv, nu);
    if (!ground) {
        out_add = vec4(max(inscatter, vec3(0.0)) * u_solar_scale + moonlight(v, false, vec3(0.0)) +
                           u_night_sky * night_sky_gradient(dot(v, -u_center_dir)),
                       0.0);
#if SKY_FIRST
        out_factor = vec4(0.0, 0.0, 0.0, 1.0);  // nothing lies behind yet: no transmittance needed
#else
        out_factor = vec4(vec3(textureLod(u_sky_third, uv, 0.0)), 1.0);
#endif
        return;
    }
    vec3 third = vec3(textureLod(u_sky_third, uv, 0.0));
    vec3 reflectance = (surface && geo.a >= 0.0) ? geo.rgb : u_atm.ground_albedo;  // no body drawn: robust fallback
    vec3 tint = vec3(1.0);
#if SKY_ILLUSTRATIVE
    if (surface) {  // the region of the surface point, as a display colour
        vec4 hit = sphere_hit(v, u_center_dir, u_sin_alpha);
        if (hit.w >= 0.0) tint = eclipse_light(u_ecl, u_eclipse_lut, u_eclipse_lut_size, hit.xyz * u_distances_m.y);
    }
#endif
    out_add = vec4((max(reflectance * third + inscatter, vec3(0.0)) * u_solar_scale + moonlight(v, true, reflectance)) * tint, 0.0);
    out_factor = vec4(0.0, 0.0, 0.0, 1.0);
}

#if SKY_HALF == 2 || SKY_MAP
// What the body pass would have written into the G-buffer: (reflectance, 0) where the ray meets
// the planet (the same hit and map coordinates as body.frag), else "nothing drawn".
vec4 surface_reflectance(vec3 v) {
    vec4 hit = sphere_hit(v, u_center_dir, u_sin_alpha);
    if (hit.w < 0.0) return vec4(0.0, 0.0, 0.0, -1.0);
    return vec4(u_reflectance * textureLod(u_body_map, body_map_uv(u_channel_to_body, hit.xyz), u_map_lod).rgb, 0.0);
}
#endif

#if !SKY_OUTSIDE
// A camera inside the atmosphere: the ray starts at the camera, so (r, mu) are the camera's; no
// inverse trigonometry per pixel. Without SKY_GEOMETRY nothing but this planet can be drawn in
// front of the air's far end (the CPU checked that no other body meets the shell), so a ray that
// meets the ground shows the surface.
// The G-buffer is fetched only where it is read: on the ground, or with SKY_GEOMETRY everywhere
// (llvmpipe skips a fetch that no pixel of a block takes).
void shade(vec3 v, ivec2 px) {
    vec3 up = -u_center_dir;
    float r = max(u_d_m, u_atm.bottom_radius_m + 1.0);
    float mu = dot(v, up);
    bool ground = atm_ray_hits_ground(u_atm, r, mu);
#if SKY_HALF == 1
    if (ground) discard;
    ground = false;
#elif SKY_HALF == 2
    if (!ground) discard;
    ground = true;
#endif
    bool surface = ground;
    vec4 geo = vec4(0.0, 0.0, 0.0, -1.0);
#if SKY_HALF == 2
    geo = surface_reflectance(v);
#elif SKY_HALF == 1
#else
    if (SKY_GEOMETRY != 0 || ground) geo = texelFetch(u_geometry, px, 0);
#endif
#if SKY_GEOMETRY
    float g = geo.a;
    if (g >= 0.0) {  // this planet's surface (the body pass's own hit decides), or something in front
        bool in_front;
        if (SKY_TERRAIN != 0) {
            in_front = true;
        } else if (ground) {
            vec4 hit = sphere_hit(v, u_center_dir, u_sin_alpha);
            surface = hit.w >= 0.0 && g >= sphere_hit_distance(v, u_center_dir, hit.w, u_distances_m) * (1.0 - 1e-3);
            in_front = !surface;
        } else {
            in_front = g < atm_distance_to_top(u_atm, r, mu);
        }
        if (in_front) {
            march_to_geometry(atm_ray_start(u_atm, u_d_m, v, u_center_dir, u_sun), g);
            return;
        }
    }
#endif
    vec2 uv = atm_sky_view_inside_uv(u_atm, v, up, u_mu_h, u_sun_perp, ground, u_sky_size);
    from_table(uv, dot(v, u_sun), ground, surface, geo, v);
}
#else
// A camera outside: the ray enters the top sphere first.
void shade(vec3 v, ivec2 px) {
    AtmosphereRayStart st = atm_ray_start(u_atm, u_d_m, v, u_center_dir, u_sun);
#if SKY_MAP
    // Nothing can lie in front of the air (the CPU checked) and the body pass did not draw the
    // planet: its own hit decides the surface, and the map gives its reflectance.
    if (!st.valid) {  // the ray misses the air
        keep_scene();
        return;
    }
    vec4 geo = surface_reflectance(v);
    bool surface = geo.a >= 0.0;
#else
    vec4 geo = texelFetch(u_geometry, px, 0);  // a body in front of the air is seen from anywhere
    float g = geo.a;
    if (!st.valid || (g >= 0.0 && g <= st.offset_m)) {  // the ray misses the air, or a body in front of it
        keep_scene();
        return;
    }
    // This planet's surface? The body pass's own hit, recomputed with the same code and uniforms
    // (as atmosphere.frag decides it).
    vec4 hit = sphere_hit(v, u_center_dir, u_sin_alpha);
    bool surface = false;
    if (hit.w >= 0.0) {
        surface = g < 0.0 || g >= sphere_hit_distance(v, u_center_dir, hit.w, u_distances_m) * (1.0 - 1e-3);
    }
#endif
    bool ground = surface || atm_ray_hits_ground(u_atm, st.r_m, st.mu);
#if SKY_GEOMETRY && !SKY_MAP
    if (g >= 0.0 && (SKY_TERRAIN != 0 || (!surface && g < st.offset_m + atm_view_ray_length(u_atm, st, -1.0)))) {
        march_to_geometry(st, g);
        return;
    }
#endif
    from_table(atm_sky_view_pixel_uv(u_atm, u_d_m, v, u_center_dir, u_sun, st, ground, u_sky_size), st.nu, ground,
               surface, geo, v);
}
#endif

#if SKY_OUTSIDE && SKY_MAP
// A planet a few pixels across, seen from outside: its bright rim of air and its map are finer
// than a pixel, so the pixel is the mean of n x n rays over its area (what it draws is then its
// light, not the luck of where one ray falls).
void shade_area(vec2 xy, int n) {
    vec4 add = vec4(0.0), factor = vec4(0.0);
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            shade(channel_ray(xy + (vec2(i, j) + 0.5) / float(n) - 0.5, u_size, u_tangents), ivec2(xy));
            add += out_add;
            factor += out_factor;
        }
    }
    out_add = add / float(n * n);
    out_factor = factor / float(n * n);
}
#endif

void main() {
#if SKY_OUTSIDE && SKY_MAP
    if (u_supersample > 1) {
        shade_area(gl_FragCoord.xy, u_supersample);
    } else {
        shade(channel_ray(gl_FragCoord.xy, u_size, u_tangents), ivec2(gl_FragCoord.xy));
    }
#else
    shade(channel_ray(gl_FragCoord.xy, u_size, u_tangents), ivec2(gl_FragCoord.xy));
#endif
    // A planet between point and disc: added times its weight, hiding nothing (as atmosphere.frag).
    out_add.rgb *= u_disc_weight;
    if (u_disc_weight < 1.0) out_factor.rgb = vec3(1.0);
#if SKY_HALO
    // The glare's halo, upsampled as glare_upsample.frag does it, added last (nothing after this
    // draw multiplies the colour): the same sum as the glare pass's own additive draw.
    out_add.rgb += textureLod(u_halo, gl_FragCoord.xy * u_halo_map.xy + u_halo_map.zw, 0.0).rgb;
#endif
#if SKY_FIRST
    out_add.a = 1.0;  // written, not blended: the coverage a cleared colour would have had
#endif
}

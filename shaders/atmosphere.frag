#version 450 core
// Deferred atmosphere of one planet, per pixel of the channel (slave/passes/atmosphere_pass.hpp):
//   out = surface_or_background * T + in-scatter (the background through dual-source blending),
// with T and the in-scatter of the production model along the view ray (ray march through the
// tables, or the analytic fast mode) up to the ground, the top of the atmosphere, or the scene
// geometry in front. Where the pixel shows this planet's surface, the surface is relit through
// the atmosphere: reflectance / pi * (direct Sun through the air + sky irradiance). Only
// directions and camera-relative ratios/distances enter (d, c_hat from the CPU in double).
// Eclipse shadows (u_ecl, positions relative to the planet centre in the channel frame) dim the
// sunlight on the relit surface and at every march sample: the Moon's shadow makes a hole in
// the in-scattered light and the sky darkens around an observer in totality.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_center_dir;   // unit, channel frame: camera -> planet centre
uniform float u_sin_alpha;   // R / d (at most 1), as the body pass had it
uniform vec4 u_distances_m;  // (d, R, d - R, d + R) in metres, as the body pass had them
uniform float u_d_m;         // camera -> planet centre, metres
uniform vec3 u_sun;          // unit, channel frame: planet centre -> Sun
uniform float u_solar_scale; // scene irradiance of the Sun / illuminance of the physical spectrum
uniform vec3 u_night_sky;    // the night sky's own glow at the zenith, scene units (shared/night_sky.glsl)
uniform AtmosphereParams u_atm;
uniform AtmosphereAnalyticFit u_fit;
uniform int u_analytic;
uniform int u_use_ms;
uniform int u_samples;
uniform vec2 u_trans_size;
uniform vec2 u_ms_size;
uniform vec2 u_irr_size;
uniform float u_weight_count;
uniform sampler2D u_geometry;  // (reflectance, distance); distance < 0: nothing drawn
uniform sampler2D u_transmittance;
uniform sampler2D u_multiple_scattering;
uniform sampler2D u_irradiance;
uniform sampler2D u_weights;
uniform EclipseCasters u_ecl;
uniform sampler2D u_eclipse_lut;
uniform vec2 u_eclipse_lut_size;
uniform float u_disc_weight;  // the planet's disc weight from point to disc (passes/planet_light): 0..1

// Blended in place (dual-source, as atmosphere_lookup.frag): colour = out_add + colour so far * out_factor.
layout(location = 0, index = 0) out vec4 out_add;
layout(location = 0, index = 1) out vec4 out_factor;

// Per unit solar irradiance at the sample wavelengths -> linear sRGB in scene units; negative
// (out of gamut) components are clipped.
vec3 to_scene_rgb(vec3 f) {
    return max(xyz_to_linear_srgb(atm_samples_to_xyz(f, u_weights, u_weight_count)), vec3(0.0)) * u_solar_scale;
}

void shade() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 geo = texelFetch(u_geometry, px, 0);
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    AtmosphereRayStart st = atm_ray_start(u_atm, u_d_m, v, u_center_dir, u_sun);
    if (!st.valid) {  // the ray misses the atmosphere
        out_add = vec4(0.0);
        out_factor = vec4(1.0);
        return;
    }
    float g = geo.a;
    bool ground = atm_ray_hits_ground(u_atm, st.r_m, st.mu);

    // This planet's surface? The body pass's own hit, recomputed with the same code and
    // uniforms, tells it exactly (comparing g with the atmosphere's ground distance would not:
    // -r mu - sqrt(disc) cancels in float metres above the ground); unless the geometry shows
    // something clearly in front of it.
    vec4 hit = sphere_hit(v, u_center_dir, u_sin_alpha);
    bool surface = false;
    float t_hit = -1.0;
    if (hit.w >= 0.0) {
        t_hit = sphere_hit_distance(v, u_center_dir, hit.w, u_distances_m);
        surface = g < 0.0 || g >= t_hit * (1.0 - 1e-3);
    }

    // Illustrative shadows: the air is drawn unshadowed and each pixel showing the surface is
    // tinted (RGB) by the region of its surface point, so the whole penumbra shows.
    bool illustrative = u_ecl.count > 0 && u_ecl.mode == ECLIPSE_MODE_ILLUSTRATIVE;
    vec3 tint = vec3(1.0);
    vec3 base = vec3(0.0);  // the relit surface; else the scene so far, through out_factor
    float t_geometry;
    if (surface) {
        vec3 reflectance = g >= 0.0 ? geo.rgb : u_atm.ground_albedo;  // no body drawn: robust fallback
        float mu_s_g = clamp(dot(hit.xyz, u_sun), -1.0, 1.0);
        vec3 illuminance;  // horizontal surface, per unit solar irradiance
        if (u_analytic != 0) {
            illuminance = atm_analytic_sun(u_fit, mu_s_g) * max(mu_s_g, 0.0);
        } else {
            illuminance = atm_surface_illuminance(u_atm, u_transmittance, u_trans_size, u_irradiance, u_irr_size,
                                                  u_atm.bottom_radius_m, mu_s_g);
        }
        vec3 light = vec3(1.0);
        if (u_ecl.count > 0) {  // direct Sun and sky light alike (the sky over a shadow is shadowed)
            light = eclipse_light(u_ecl, u_eclipse_lut, u_eclipse_lut_size, hit.xyz * u_distances_m.y);
        }
        if (illustrative) {  // a display colour, applied in RGB to the whole pixel below
            tint = light;
            light = vec3(1.0);
        }
        base = reflectance * to_scene_rgb(illuminance * light) * (1.0 / CUPOLA_PI);
        // -1: the march ends exactly at the ground; a grazing ray the atmosphere thinks misses
        // the ground ends at the surface.
        t_geometry = ground ? -1.0 : max(g, t_hit);
    } else {
        t_geometry = g;
    }

    // The march's start (the camera moved st.offset_m along v), relative to the planet centre.
    EclipseRay shadow = eclipse_ray(u_ecl, u_eclipse_lut_size, v * st.offset_m - u_center_dir * u_d_m, v);
    if (illustrative) {
        shadow.casters.count = 0;
    }
    AtmosphereSegment seg;
    if (u_analytic != 0) {
        seg = atm_analytic_view_ray(u_atm, u_fit, st, t_geometry);
        // The fast model lights the whole ray with the sunlight at its middle; so its shadow.
        seg.inscatter_per_sr = seg.inscatter_per_sr *
                        eclipse_light_along(shadow, u_eclipse_lut, 0.5 * atm_view_ray_length(u_atm, st, t_geometry));
    } else {
        seg = atm_view_ray_shadowed(u_atm, u_transmittance, u_trans_size, u_multiple_scattering, u_ms_size,
                                    u_use_ms != 0, st, t_geometry, u_samples, shadow, u_eclipse_lut);
    }
    vec3 glow = ground ? vec3(0.0) : u_night_sky * night_sky_gradient(dot(v, -u_center_dir));
    out_add = vec4((base * seg.transmittance + to_scene_rgb(seg.inscatter_per_sr)) * tint + glow, 0.0);
    out_factor = surface ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(seg.transmittance * tint, 1.0);
}

// A planet between point and disc (u_disc_weight < 1): its air and ground are added times the
// weight over what lies behind, and hide none of it: the planet's own point, drawn before the air,
// lies there, and the few pixels of stars behind so small a disc are not worth hiding.
void main() {
    shade();
    out_add.rgb *= u_disc_weight;
    if (u_disc_weight < 1.0) out_factor.rgb = vec3(1.0);
}

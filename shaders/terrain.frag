#version 450 core
// A terrain tile's surface: the map's reflectance at the point (body_map_uv), lit by the Sun on the
// slope where the relief does not shadow it and by the sky it sees (shared/terrain_light.glsl).
// With an atmosphere (TERRAIN_AIR) both come from the atmosphere's tables at the point, the Sun's
// light through the air to it; the atmosphere pass then adds the air between the camera and the
// point (its march to scene geometry, slave/passes/atmosphere_pass.hpp). Writes the deferred geometry as body.frag does
// (reflectance, distance) and a logarithmic depth, so the relief hides itself.
in vec3 v_channel_m;
in vec3 v_body_m;
in vec3 v_normal;
in float v_sun_seen;  // the relief's shadow (terrain.vert)
uniform sampler2D u_texture;      // the body's map, linear RGB, row 0 = north
uniform vec3 u_reflectance;       // albedo * tint
uniform float u_pixel_rad;        // a pixel's angle (the channel's, at its centre)
uniform float u_texel_m;          // a texel of the map's finest level on the ground, at the equator
uniform vec3 u_sun_body;          // unit, body frame, from the body toward the Sun
uniform vec3 u_lit;               // no air: the Sun's irradiance / pi (scene units)
#if TERRAIN_AIR
uniform AtmosphereParams u_atm;
uniform sampler2D u_transmittance;
uniform sampler2D u_irradiance;
uniform sampler2D u_weights;
uniform vec2 u_trans_size;
uniform vec2 u_irr_size;
uniform float u_weight_count;
uniform float u_solar_scale;
#endif

layout(location = 0) out vec4 frag_color;
layout(location = 1) out vec4 frag_geometry;

void main() {
    vec3 up = normalize(v_body_m);
    vec3 n = normalize(v_normal);
    float distance_m = length(v_channel_m);
    // The map's level whose texel matches the pixel's footprint on the ground (from the distance,
    // not screen derivatives, which jump where the longitude wraps).
    float lod = max(log2(max(distance_m * u_pixel_rad / u_texel_m, 1e-30)), 0.0);
    vec3 reflectance = u_reflectance * textureLod(u_texture, body_map_uv(mat3(1.0), up), lod).rgb;
    float mu_s = dot(up, u_sun_body);
#if TERRAIN_AIR
    float r = max(length(v_body_m), u_atm.bottom_radius_m + 1.0);
    vec3 direct = atm_sun_transmittance(u_atm, u_transmittance, u_trans_size, r, mu_s) * v_sun_seen;
    vec3 sky = atm_lookup_irradiance(u_atm, u_irradiance, u_irr_size, r, mu_s);
    vec3 e = terrain_illuminance(direct, sky, n, up, u_sun_body);
    vec3 radiance = reflectance * (1.0 / CUPOLA_PI) * atm_samples_to_rgb(e, u_weights, u_weight_count) * u_solar_scale;
#else
    vec3 radiance = reflectance * u_lit * max(dot(n, u_sun_body), 0.0) * v_sun_seen;
#endif
    frag_color = vec4(max(radiance, vec3(0.0)), 1.0);
    frag_geometry = vec4(reflectance, distance_m);
    gl_FragDepth = log_depth(distance_m);
}

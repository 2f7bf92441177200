#version 450 core
// A planet or moon: analytic ray-sphere hit, equirectangular texture in the body frame
// (lon = atan(y, x), north = +Z), Lambert-lit by the sun. Also writes the deferred geometry
// the atmosphere pass reads: diffuse reflectance (linear) and the hit distance in metres, and a
// logarithmic depth of that distance for the glare probe's occlusion queries.
// Eclipse shadows: the sunlight at the surface point (normal * radius, relative to the centre,
// like the casters in u_ecl) is scaled by eclipse_light (shaders/shared/eclipse_casters.glsl),
// only in the BODY_ECLIPSE variant (slave/passes/body_pass.cpp): on a CPU rasteriser a branch
// costs whether taken or not, and a body whose atmosphere relights its surface needs none.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_center_dir;       // unit, channel frame
uniform float u_sin_alpha;       // R / d
uniform vec4 u_distances_m;      // (d, R, d - R, d + R) in metres, from the CPU in double
uniform mat3 u_channel_to_body;
uniform vec3 u_sun_dir;          // unit, channel frame, from the body towards the sun
uniform vec3 u_lit;              // albedo / pi * irradiance * tint
uniform vec3 u_reflectance;      // albedo * tint
uniform sampler2D u_texture;     // linear RGB, row 0 = north
uniform EclipseCasters u_ecl;    // channel frame, metres from the body's centre
uniform sampler2D u_eclipse_lut;
uniform vec2 u_eclipse_lut_size;

layout(location = 0) out vec4 frag_color;
layout(location = 1) out vec4 frag_geometry;  // (reflectance, distance)

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    vec4 hit = sphere_hit(v, u_center_dir, u_sin_alpha);
    if (hit.w < 0.0) {
        discard;
    }
    vec3 n = hit.xyz;
    vec3 albedo_map = textureLod(u_texture, body_map_uv(u_channel_to_body, n), 0.0).rgb;
    float cos_i = max(dot(n, u_sun_dir), 0.0);
    vec3 light = vec3(1.0);
#if BODY_ECLIPSE
    if (u_ecl.count > 0 && cos_i > 0.0) {
        light = eclipse_light(u_ecl, u_eclipse_lut, u_eclipse_lut_size, n * u_distances_m.y);
    }
#endif
    frag_color = vec4(u_lit * cos_i * albedo_map * light, 1.0);
    float distance_m = sphere_hit_distance(v, u_center_dir, hit.w, u_distances_m);
    frag_geometry = vec4(u_reflectance * albedo_map, distance_m);
    gl_FragDepth = log_depth(distance_m);  // only a depth target (the glare probe) keeps it
}

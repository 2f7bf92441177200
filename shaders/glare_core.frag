#version 450 core
// The glare's core of one source at full resolution, on a billboard only as large as the core
// (slave/passes/glare_pass.hpp): the smooth part of the PSF (glare_psf_smooth) times the core's
// share (glare_core_share); the halo target holds the rest, the ray wedges the rays.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform GlareParams u_glare;
uniform vec3 u_center;
uniform vec3 u_irradiance;
uniform vec2 u_core_rad;  // inner and outer angle of the core

layout(location = 0) out vec4 frag_color;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    float theta = angle_between_units(v, u_center);
    GlareParams p = u_glare;
    p.streak_contrast = glare_ray_contrast(u_glare, theta, length(fwidth(v)));
    float share = glare_core_share(theta, u_core_rad.x, u_core_rad.y);
    frag_color = vec4(u_irradiance * glare_psf_smooth(p, theta) * share, 0.0);
}

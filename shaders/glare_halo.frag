#version 450 core
// The glare's wide, smooth halo of one source at reduced resolution (slave/passes/glare_halo_pass.hpp):
// the part of the PSF without azimuth (glare_psf_smooth) times the halo's share (1 - the core's,
// glare_core_share), into the low-resolution halo target, additive. Each texel is the value at
// its centre's direction; the texel grid is fixed to the channel's axis (GlareHaloGrid), so
// channels that share an image plane share the texels.
uniform vec4 u_tangents;  // of the halo grid (guard band included)
uniform vec2 u_size;      // texels
uniform GlareParams u_glare;
uniform vec3 u_center;
uniform vec3 u_irradiance;
uniform vec2 u_core_rad;     // the core's inner and outer angle
uniform float u_pixel_scale;  // full-resolution pixel / halo texel (1 / downsample)

layout(location = 0) out vec4 frag_color;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    float theta = angle_between_units(v, u_center);
    GlareParams p = u_glare;
    // The rays' contrast as the full-resolution pixels see it (their energy stays in the smooth
    // part where they fade).
    p.streak_contrast = glare_ray_contrast(u_glare, theta, length(fwidth(v)) * u_pixel_scale);
    float share = 1.0 - glare_core_share(theta, u_core_rad.x, u_core_rad.y);
    frag_color = vec4(u_irradiance * glare_psf_smooth(p, theta) * share, 0.0);
}

#version 450 core
// Glare of one source (Ekelin & Fernqvist 2009, sections 2.3 and 3.1; Spencer et al. 1995,
// shared/glare_psf.glsl):
// bloom, lenticular halo and ciliary-corona streaks, added to the linear HDR image before any
// tone mapping. The billboard (sphere.vert's corners) only bounds the work: the radiance is a
// function of the view direction alone -- the angle from the glare centre and the azimuth in
// the cluster-wide glare frame -- so every channel that sees a direction draws the same value.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform GlareParams u_glare;
uniform vec3 u_center;      // unit, channel frame: the source's centre moved toward its visible part
uniform vec3 u_e1;          // glare frame axes, channel frame
uniform vec3 u_e2;
uniform vec3 u_irradiance;  // rgb: irradiance x visible fraction

layout(location = 0) out vec4 frag_color;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    // The rays are thin; where one is narrower than about a pixel, point sampling would alias
    // them (shimmer as the glare moves), so their contrast fades there. The streaks' mean is 1
    // at any contrast, so the glare's energy does not change.
    GlareParams p = u_glare;
    float pixel_rad = length(fwidth(v));
    float ray_rad = angle_between_units(v, u_center) * (2.0 * CUPOLA_PI / max(p.streak_count, 2.0)) * 0.2;
    p.streak_contrast *= clamp((ray_rad / max(pixel_rad, 1e-9) - 0.5) / 1.5, 0.0, 1.0);
    frag_color = vec4(glare_radiance(p, v, u_center, u_e1, u_e2, u_irradiance), 0.0);
}

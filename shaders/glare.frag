#version 450 core
// Glare of one source evaluated per pixel: the full-resolution path (glare.halo_downsample 1)
// and the reference of the split one (glare_halo.frag, glare_core.frag, glare_rays.vert/.frag).
// Ekelin & Fernqvist 2009, sections 2.3 and 3.1; Spencer et al. 1995 (shared/glare_psf.glsl):
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
    // The rays' contrast fades where they are narrower than about a pixel (glare_ray_contrast).
    GlareParams p = u_glare;
    p.streak_contrast = glare_ray_contrast(u_glare, angle_between_units(v, u_center), length(fwidth(v)));
    frag_color = vec4(glare_radiance(p, v, u_center, u_e1, u_e2, u_irradiance), 0.0);
}

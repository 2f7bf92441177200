#version 450 core
// Limb-darkened stellar disc: the view ray meets the sphere analytically; mu gives the darkening.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_center_dir;  // unit, channel frame
uniform float u_sin_alpha;  // R / d
uniform vec3 u_radiance;    // disc-centre radiance times tint
uniform float u_limb_u;

out vec4 frag_color;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    vec4 hit = sphere_hit(v, u_center_dir, u_sin_alpha);
    if (hit.w < 0.0) {
        discard;
    }
    frag_color = vec4(u_radiance * limb_darkening(hit.w, u_limb_u), 1.0);
}

#version 450 core
// Limb-darkened stellar disc: the view ray meets the sphere analytically; mu gives the darkening.
// Also writes the deferred geometry (no diffuse reflectance, hit distance in metres) so that an
// atmosphere behind the disc leaves it alone.
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_center_dir;  // unit, channel frame
uniform float u_sin_alpha;  // R / d
uniform vec4 u_distances;   // (d, R, d - R, d + R) in metres, from the CPU in double
uniform vec3 u_radiance;    // disc-centre radiance times tint
uniform float u_limb_u;

layout(location = 0) out vec4 frag_color;
layout(location = 1) out vec4 frag_geometry;

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    vec4 hit = sphere_hit(v, u_center_dir, u_sin_alpha);
    if (hit.w < 0.0) {
        discard;
    }
    frag_color = vec4(u_radiance * limb_darkening(hit.w, u_limb_u), 1.0);
    frag_geometry = vec4(0.0, 0.0, 0.0, sphere_hit_distance(v, u_center_dir, hit.w, u_distances));
}

#version 450 core
// Limb-darkened stellar disc and its corona. The view ray meets the sphere analytically; mu
// gives the darkening. Around the disc, out to CORONA_EXTENT solar radii, the corona: Baumbach's
// mean brightness profile (Allen's Astrophysical Quantities), relative to the disc's mean
// radiance,
//   B(rho) / B_disc = 1e-6 (0.0532 rho^-2.5 + 1.425 rho^-7 + 2.565 rho^-17),  rho in radii,
// times the scene's `corona` factor. It is always drawn (added over the stars behind it); about
// a millionth of the disc, it shows only once the Moon covers the disc and the atmosphere's
// in-scatter falls with the visible fraction, i.e. in totality.
// The disc also writes the deferred geometry (no diffuse reflectance, hit distance in metres) so
// that an atmosphere behind the disc leaves it alone; the corona leaves "background".
uniform vec4 u_tangents;
uniform vec2 u_size;
uniform vec3 u_center_dir;     // unit, channel frame
uniform float u_sin_alpha;     // of the billboard's sphere (the corona's extent)
uniform vec4 u_distances_m;    // of the billboard's sphere (unused)
uniform float u_disc_sin_alpha;  // R / d of the disc itself
uniform vec4 u_disc_distances_m; // (d, R, d - R, d + R) of the disc in metres, from the CPU in double
uniform vec3 u_radiance;       // disc-centre radiance times tint
uniform float u_limb_u;
uniform float u_corona;        // 0: no corona

layout(location = 0) out vec4 frag_color;
layout(location = 1) out vec4 frag_geometry;

const float CORONA_EXTENT = 6.0;

float corona_profile(float rho) {
    return 1e-6 * (0.0532 * pow(rho, -2.5) + 1.425 * pow(rho, -7.0) + 2.565 * pow(rho, -17.0));
}

void main() {
    vec3 v = channel_ray(gl_FragCoord.xy, u_size, u_tangents);
    vec4 hit = sphere_hit(v, u_center_dir, u_disc_sin_alpha);
    if (hit.w >= 0.0) {
        frag_color = vec4(u_radiance * limb_darkening(hit.w, u_limb_u), 1.0);
        frag_geometry = vec4(0.0, 0.0, 0.0, sphere_hit_distance(v, u_center_dir, hit.w, u_disc_distances_m));
        return;
    }
    float theta = angle_between_units(v, u_center_dir);
    float rho = sin(min(theta, 1.5707963)) / u_disc_sin_alpha;
    if (u_corona <= 0.0 || theta >= 1.5707963 || rho >= CORONA_EXTENT) {
        discard;
    }
    vec3 mean_disc = u_radiance * limb_darkening_disc_average(u_limb_u);
    frag_color = vec4(mean_disc * (u_corona * corona_profile(max(rho, 1.0))), 1.0);
    frag_geometry = vec4(0.0, 0.0, 0.0, -1.0);
}

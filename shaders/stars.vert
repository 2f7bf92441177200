#version 450 core
// Star sprites: one GL point per catalogue star, sized from the local pixel scale so that it
// covers 4 sigma of the angular PSF (at least 3 px). The fragment shader integrates the PSF over
// each pixel it covers.
layout(location = 0) in vec3 a_dir;   // unit direction, world frame
layout(location = 1) in float a_flux; // zero_mag_flux * 10^(-0.4 V), scene units x sr
layout(location = 2) in float a_bv;   // B-V colour index

uniform mat3 u_world_to_channel;
uniform mat4 u_projection;      // the channel frustum widened by a guard band
uniform vec2 u_px_per_tangent;  // pixels per unit of tangent-plane coordinate (x, y)
uniform float u_sigma_rad;      // PSF sigma, radians

flat out vec3 v_color;    // flux times the unit-luminance B-V colour
flat out vec2 v_t;        // tangent-plane point of the star
flat out vec2 v_sigma_t;  // tangent-plane sigmas of its PSF

void main() {
    vec3 d = u_world_to_channel * a_dir;
    v_color = a_flux * bv_to_linear_srgb(a_bv);
    gl_Position = u_projection * vec4(d, 1.0);
    float zc = min(d.z, -1e-3);
    float tx = d.x / -zc;
    float ty = d.y / -zc;
    v_t = vec2(tx, ty);
    v_sigma_t = star_tangent_sigma(v_t, u_sigma_rad);
    // Pixels per radian: the tangent plane stretches angles by up to 1 + tan^2 off axis.
    float px_per_rad = max(u_px_per_tangent.x, u_px_per_tangent.y) * (1.0 + tx * tx + ty * ty);
    gl_PointSize = min(max(3.0, 2.0 * ceil(4.0 * u_sigma_rad * px_per_rad + 1.0) + 1.0), 255.0);
}

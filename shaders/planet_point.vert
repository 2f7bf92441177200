#version 450 core
// A planet or moon too small to draw as a disc, or fading between point and disc
// (slave/passes/planet_light.hpp): one GL point at its direction, sized like a star's sprite
// (stars.vert) to cover its PSF out to where it can still change a display pixel.
uniform vec3 u_dir;             // unit, channel frame
uniform vec3 u_color;           // its flux (scene units x sr) times the unit-luminance colour
uniform float u_sigma_rad;      // its PSF: the stars' sigma widened by the disc's size
uniform mat4 u_projection;      // the channel frustum
uniform vec2 u_px_per_tangent;  // pixels per unit of tangent-plane coordinate (x, y)
uniform float u_exposure;       // the snapshot's; <= 0: u_fixed_reach_sigma
uniform float u_min_display;
uniform float u_fixed_reach_sigma;

flat out vec2 v_t;        // tangent-plane point of the body
flat out vec2 v_sigma_t;  // tangent-plane sigmas of its PSF

void main() {
    gl_Position = u_projection * vec4(u_dir, 1.0);
    float zc = min(u_dir.z, -1e-3);
    v_t = vec2(u_dir.x / -zc, u_dir.y / -zc);
    v_sigma_t = star_tangent_sigma(v_t, u_sigma_rad);
    float px_per_rad = max(u_px_per_tangent.x, u_px_per_tangent.y) * (1.0 + dot(v_t, v_t));
    float reach_sigma = u_fixed_reach_sigma;
    if (u_exposure > 0.0) {
        float peak = max(u_color.r, max(u_color.g, u_color.b)) / (2.0 * CUPOLA_PI * u_sigma_rad * u_sigma_rad);
        reach_sigma = sqrt(2.0 * log(max(peak * u_exposure / u_min_display, 1.0)));
    }
    gl_PointSize = clamp(ceil(2.0 * reach_sigma * u_sigma_rad * px_per_rad) + 2.0, 1.0, 255.0);
}

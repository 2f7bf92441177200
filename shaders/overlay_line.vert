#version 450 core
// Overlay lines (slave/passes/overlay_pass.hpp): each arc of a circle on the sky (common/overlay/
// sky_arcs.hpp) is a quad on the unit sphere around it, as wide as the line plus a margin for the
// anti-aliasing ramp. Directions are at infinity: drawn at unit distance, in the channel frame.
// Every overlay's arcs are in one buffer; each vertex names its overlay, whose frame, colour and
// width are this frame's uniforms.
const int kOverlays = 10;  // common/overlay/overlay_kind.hpp, kOverlayCount

layout(location = 0) in vec3 a_dir;       // a point of the circle, the overlay's frame
layout(location = 1) in vec3 a_pole;      // the circle's pole, the overlay's frame
layout(location = 2) in float a_lat;      // the circle's latitude about its pole, radians
layout(location = 3) in float a_side;     // -1 or +1: which edge of the band
layout(location = 4) in float a_overlay;  // the overlay (OverlayKind)

uniform mat3 u_to_channel[kOverlays];  // overlay frame -> channel frame
uniform vec4 u_color[kOverlays];       // rgb: display colour / exposure; a: the overlay's opacity
uniform vec4 u_line[kOverlays];        // x: half the line's width, radians
uniform mat4 u_projection;
uniform float u_margin_rad;  // the widest pixel's angle, and more: room for the ramp

out vec3 v_dir;
flat out vec3 v_pole;
flat out vec2 v_lat;  // sin and 1 / cos of the circle's latitude
flat out vec4 v_color;
flat out float v_half_width_rad;

void main() {
    int k = clamp(int(a_overlay + 0.5), 0, kOverlays - 1);
    vec3 d = u_to_channel[k] * a_dir;
    vec3 pole = u_to_channel[k] * a_pole;
    vec3 toward = pole - dot(pole, d) * d;  // on the sphere at d, toward the pole: across the line
    float n = length(toward);
    toward = n > 1e-6 ? toward / n : vec3(0.0);
    float half_width_rad = u_line[k].x;
    vec3 p = normalize(d + toward * tan(a_side * (half_width_rad + u_margin_rad)));
    v_dir = p;
    v_pole = pole;
    v_lat = vec2(sin(a_lat), 1.0 / cos(a_lat));
    v_color = u_color[k];
    v_half_width_rad = half_width_rad;
    gl_Position = u_projection * vec4(p, 1.0);
}

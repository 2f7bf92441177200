#version 450 core
// Overlay text (slave/passes/overlay_pass.hpp): a label is a quad on the unit sphere around its
// anchor, upright toward u_up (the zenith, or the celestial pole), its corners given as angles in
// the tangent plane, so the text is as large in dome degrees on every channel. Every overlay's
// labels are in one buffer; each vertex names its overlay, whose frame and colour are uniforms.
const int kOverlays = 10;  // common/overlay/overlay_kind.hpp, kOverlayCount

layout(location = 0) in vec3 a_anchor;    // the overlay's frame
layout(location = 1) in vec2 a_corner;    // tangent-plane offsets (right, up), radians
layout(location = 2) in vec2 a_uv;        // the glyphs' atlas
layout(location = 3) in float a_overlay;  // the overlay (OverlayKind)

uniform mat3 u_to_channel[kOverlays];  // overlay frame -> channel frame
uniform vec4 u_color[kOverlays];       // rgb: display colour / exposure; a: the overlay's opacity
uniform mat4 u_projection;
uniform vec3 u_up;  // channel frame

out vec2 v_uv;
flat out vec4 v_color;

void main() {
    int k = clamp(int(a_overlay + 0.5), 0, kOverlays - 1);
    vec3 p = u_to_channel[k] * a_anchor;
    vec3 up = u_up - dot(u_up, p) * p;
    if (length(up) < 1e-4) up = abs(p.y) < 0.9 ? vec3(0.0, 1.0, 0.0) - p.y * p : vec3(1.0, 0.0, 0.0) - p.x * p;
    up = normalize(up);
    vec3 right = cross(p, up);
    vec3 d = normalize(p + a_corner.x * right + a_corner.y * up);
    v_uv = a_uv;
    v_color = u_color[k];
    gl_Position = u_projection * vec4(d, 1.0);
}

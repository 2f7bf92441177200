#version 450 core
// A pixel's share of an overlay line: its own direction's angle to the circle against the line's
// half width, ramped over the angle a pixel spans there (the derivatives), so the line is as wide
// in dome degrees on every channel and anti-aliased at any resolution. Blended over the frame.
in vec3 v_dir;
flat in vec3 v_pole;
flat in vec2 v_lat;    // sin and 1 / cos of the circle's latitude
flat in vec4 v_color;  // rgb: display colour / exposure; a: the overlay's opacity
flat in float v_half_width_rad;

out vec4 frag_color;

void main() {
    // The signed angle to the circle, to first order (asin(sin(lat) + e) - lat = e / cos(lat) +
    // O(e^2 tan(lat) / 2): at the edge of a 0.1 degree line on the 80 degree parallel, 2e-4 degrees).
    float s = (dot(normalize(v_dir), v_pole) - v_lat.x) * v_lat.y;
    float px = max(fwidth(s), 1e-9);
    float coverage = clamp((v_half_width_rad - abs(s)) / px + 0.5, 0.0, 1.0);
    if (coverage <= 0.0) discard;
    frag_color = vec4(v_color.rgb, v_color.a * coverage);
}

#version 450 core
// The star's radiance averaged over this pixel: the PSF (an angle, cluster-wide) is integrated
// exactly over the pixel's box in the tangent plane (star_box_fraction), then divided by the
// pixel's solid angle. One evaluation per pixel at any resolution; every channel shows the same
// star with the same energy and the same centroid.
flat in vec3 v_color;     // flux times the unit-luminance B-V colour
flat in vec2 v_t;         // the star's tangent-plane point
flat in vec2 v_sigma_t;   // its tangent-plane sigmas

uniform vec4 u_tangents;  // left, right, down, up
uniform vec2 u_size;      // framebuffer size in pixels

out vec4 frag_color;

void main() {
    vec2 px = floor(gl_FragCoord.xy);
    vec2 span = vec2(u_tangents.x + u_tangents.y, u_tangents.z + u_tangents.w) / u_size;
    vec2 lo = vec2(-u_tangents.x, -u_tangents.z) + px * span;
    vec2 hi = lo + span;
    float fraction = star_box_fraction(v_t, v_sigma_t, lo, hi);
    vec2 c = 0.5 * (lo + hi);
    float q = 1.0 + dot(c, c);
    float pixel_solid_angle = span.x * span.y / (q * sqrt(q));
    frag_color = vec4(v_color * (fraction / pixel_solid_angle), 0.0);
}

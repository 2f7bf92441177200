#version 450 core
// Test and benchmark helper (tests/test_eclipse_shadow.cpp, benchmarks/eclipse_speed_vs_error.cpp):
// evaluates the shared eclipse functions on the GPU for one (a, s) pair per pixel, read from
// u_params (texel (x, y) for pixel (x, y): r = a, g = s), so the results can be compared with the
// C++ build of the same text, or timed.
uniform sampler2D u_params;
uniform sampler2D u_lut;
uniform vec2 u_lut_size;
uniform float u_limb_u;
uniform float u_order;  // fast mode: Butterworth order n
// -1: exact, fast, lut and region into rgba; ECLIPSE_MODE_* (0..3): that mode alone (illustrative:
// the region's tint); 4: none (the inputs only: the benchmark's baseline). The benchmark defines
// ECLIPSE_EVAL_MODE instead, so each of its programs holds one mode's code only.
#ifdef ECLIPSE_EVAL_MODE
const int u_mode = ECLIPSE_EVAL_MODE;
#else
uniform int u_mode;
#endif
out vec4 frag_color;

void main() {
    vec2 p = texelFetch(u_params, ivec2(gl_FragCoord.xy), 0).xy;
    float a = p.x;
    float s = p.y;
    if (u_mode == -1) {
        frag_color = vec4(eclipse_visible_exact(a, s, u_limb_u), eclipse_visible_fast(a, s, u_order),
                          eclipse_visible_lut(u_lut, u_lut_size, a, s), float(eclipse_region(a, s)));
    } else if (u_mode == ECLIPSE_MODE_EXACT) {
        frag_color = vec4(vec3(eclipse_visible_exact(a, s, u_limb_u)), 1.0);
    } else if (u_mode == ECLIPSE_MODE_FAST) {
        frag_color = vec4(vec3(eclipse_visible_fast(a, s, u_order)), 1.0);
    } else if (u_mode == ECLIPSE_MODE_LUT) {
        frag_color = vec4(vec3(eclipse_visible_lut(u_lut, u_lut_size, a, s)), 1.0);
    } else if (u_mode == ECLIPSE_MODE_ILLUSTRATIVE) {
        frag_color = vec4(eclipse_region_tint(eclipse_region(a, s)), 1.0);
    } else {
        frag_color = vec4(a, s, 0.0, 1.0);
    }
}

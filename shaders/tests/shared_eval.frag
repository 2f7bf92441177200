#version 450 core
// Test helper (tests/test_egl_render.cpp): evaluates shared shading functions on the GPU, one
// parameter pair per pixel, so the result can be compared with the C++ build of the same text.
uniform vec2 u_size;
out vec4 frag_color;

void main() {
    float a = gl_FragCoord.x / u_size.x;  // pixel centres: (i + 0.5) / n
    float b = gl_FragCoord.y / u_size.y;
    float sigma = 5.8e-4;
    float psf = star_psf(a * 4.0 * sigma, sigma) * (2.0 * CUPOLA_PI * sigma * sigma);
    float ld = limb_darkening(a, b);
    vec3 c = bv_to_linear_srgb(-0.4 + 2.4 * a);
    vec3 v = normalize(vec3(a - 0.5, b - 0.5, -1.0));
    vec4 hit = sphere_hit(v, vec3(0.0, 0.0, -1.0), 0.3);
    frag_color = vec4(psf, ld, c.x / max(c.z, 1e-6) * 0.1 + c.y, hit.w);
}

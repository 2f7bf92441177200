#version 450 core
// The star's radiance averaged over this pixel's footprint: u_subsamples^2 rays through the pixel,
// each evaluating the angular PSF. The PSF is defined in angle, so every channel (any resolution,
// any field of view) shows the same star with the same integrated flux.
flat in vec3 v_dir;
flat in vec3 v_color;

uniform vec4 u_tangents;  // left, right, down, up
uniform vec2 u_size;      // framebuffer size in pixels
uniform float u_sigma;    // radians
uniform int u_subsamples; // per axis, chosen so the spacing is at most sigma

out vec4 frag_color;

void main() {
    vec3 s = normalize(v_dir);
    vec2 corner = floor(gl_FragCoord.xy);
    float sum = 0.0;
    for (int j = 0; j < u_subsamples; j++) {
        for (int i = 0; i < u_subsamples; i++) {
            vec2 p = corner + (vec2(float(i), float(j)) + 0.5) / float(u_subsamples);
            sum += star_psf(angle_between_units(channel_ray(p, u_size, u_tangents), s), u_sigma);
        }
    }
    frag_color = vec4(v_color * (sum / float(u_subsamples * u_subsamples)), 0.0);
}

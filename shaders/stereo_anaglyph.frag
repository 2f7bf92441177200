#version 450 core
// The red-cyan anaglyph of a stereo pair (slave/stereo_packer): each pixel's two linear colours
// through Dubois's matrices (shaders/shared/stereo_anaglyph.glsl).
uniform sampler2D u_left;
uniform sampler2D u_right;
layout(location = 0) out vec4 frag_color;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 l = texelFetch(u_left, p, 0);
    vec4 r = texelFetch(u_right, p, 0);
    frag_color = vec4(dubois_anaglyph(l.rgb, r.rgb), max(l.a, r.a));
}

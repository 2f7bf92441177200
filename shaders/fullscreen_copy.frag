#version 450 core
// The trivial full-screen pass costs are measured against (benchmarks/warp_cost.cpp): one texel
// of the source per pixel, copied.
uniform sampler2D u_source;
layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = texelFetch(u_source, ivec2(gl_FragCoord.xy), 0);
}

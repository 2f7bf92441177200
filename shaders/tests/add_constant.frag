#version 450 core
// Test helper (tests/test_render_passes.cpp): adds u_add to the colour. u_sample != 0: reads the
// colour so far (u_scene) and writes the sum; else writes u_add alone, for additive blending.
// Alpha stays what it was.
uniform sampler2D u_scene;
uniform int u_sample;
uniform vec3 u_add;
layout(location = 0) out vec4 frag_color;

void main() {
    if (u_sample != 0) {
        vec4 scene = texelFetch(u_scene, ivec2(gl_FragCoord.xy), 0);
        frag_color = vec4(scene.rgb + u_add, scene.a);
    } else {
        frag_color = vec4(u_add, 0.0);
    }
}

#version 450 core
// Overlay text: the glyphs' coverage (FreeType's, mipmapped) times the overlay's colour.
in vec2 v_uv;
flat in vec4 v_color;  // rgb: display colour / exposure; a: the overlay's opacity

uniform sampler2D u_atlas;

out vec4 frag_color;

void main() {
    float coverage = texture(u_atlas, v_uv).r;
    if (coverage <= 0.0) discard;
    frag_color = vec4(v_color.rgb, v_color.a * coverage);
}

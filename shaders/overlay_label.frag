#version 450 core
// Overlay text: the glyphs' coverage (FreeType's, mipmapped) times the overlay's colour.
in vec2 v_uv;

uniform sampler2D u_atlas;
uniform vec4 u_color;  // rgb: display colour / exposure; a: the overlay's opacity

out vec4 frag_color;

void main() {
    float coverage = texture(u_atlas, v_uv).r;
    if (coverage <= 0.0) discard;
    frag_color = vec4(u_color.rgb, u_color.a * coverage);
}

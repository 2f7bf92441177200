#version 450 core
// Test helper (tests/test_cap_cover.cpp): marks every pixel the cover reaches.
layout(location = 0) out vec4 frag_color;

void main() { frag_color = vec4(1.0); }

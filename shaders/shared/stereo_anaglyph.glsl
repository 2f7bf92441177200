// Red-cyan anaglyph of a stereo pair (shared by GLSL and C++: common/shading/shared_shading.hpp).
// Dubois 2001, section 3: the colour seen through each filter of the glasses is matched in the
// least-squares sense by a projection of the two eyes' colours; for red-cyan glasses on an
// ordinary display it reduces to two 3x3 matrices applied to linear RGB, the sum clamped to the
// displayable (here: non-negative, linear light before the display curve; the output transform
// does the rest). GLSL's mat3 is given column by column: each vec3 below is one column.
const mat3 kDuboisLeft = mat3(vec3(0.437, -0.062, -0.048), vec3(0.449, -0.062, -0.050), vec3(0.164, -0.024, -0.017));
const mat3 kDuboisRight = mat3(vec3(-0.011, 0.377, -0.026), vec3(-0.032, 0.761, -0.093), vec3(-0.007, 0.009, 1.234));

// left_rgb, right_rgb: the two eyes' linear colours of one pixel. Returns the anaglyph's.
vec3 dubois_anaglyph(vec3 left_rgb, vec3 right_rgb) {
    return max(kDuboisLeft * left_rgb + kDuboisRight * right_rgb, vec3(0.0));
}

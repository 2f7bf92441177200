// A projector's blend and colour (shared by GLSL and C++: common/shading/shared_shading.hpp).
// Every value is linear light in [0, 1] of the projector's range unless it says encoded. The
// rules are those of common/calibration/projector_warp.hpp:
//   blend (VESA MPCDI v2.0 (2015)'s alpha and beta maps, with a Bourke mesh's per-point intensity):
//     C_out = C * alpha * intensity * (1 - beta) + beta
//   encode for the projector: value = C_out^(1 / gamma); decode: C = value^gamma (the rule of
//   VESA MPCDI v2.0 (2015) §2.5.1.2.4 for embedded gamma).

const int PROJECTOR_ENCODE_SRGB = 0;   // IEC 61966-2-1 curve (a monitor, an uncalibrated output)
const int PROJECTOR_ENCODE_GAMMA = 1;  // the projector's power law

// Black-level lift: the projector's own black (beta) is the floor everything is raised onto, so
// that non-overlapping parts match the brighter black of the overlaps.
vec3 projector_black_lift(vec3 c, float beta) {
    return c * (1.0 - beta) + vec3(beta);
}

// c: the content's linear value (radiance x exposure); what lies outside the projector's range
// [0, 1]^3 (above its white, or a negative component: out of gamut) is first mapped into it at
// constant luminance (gamut_map.glsl), never clipped per channel.
vec3 projector_blend(vec3 c, float alpha, float intensity, float beta) {
    return projector_black_lift(gamut_map_to_unit_cube(c) * (alpha * intensity), beta);
}

float projector_gamma_encode(float linear, float gamma) {
    return pow(clamp(linear, 0.0, 1.0), 1.0 / gamma);
}

float projector_gamma_decode(float encoded, float gamma) {
    return pow(clamp(encoded, 0.0, 1.0), gamma);
}

float projector_srgb_encode(float linear) {
    float x = clamp(linear, 0.0, 1.0);
    if (x <= 0.0031308) return 12.92 * x;
    return 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

float projector_encode_channel(float linear, float gamma, int mode) {
    if (mode == PROJECTOR_ENCODE_SRGB) return projector_srgb_encode(linear);
    return projector_gamma_encode(linear, gamma);
}

vec3 projector_encode(vec3 c, float gamma, int mode) {
    return vec3(projector_encode_channel(c.x, gamma, mode), projector_encode_channel(c.y, gamma, mode),
                projector_encode_channel(c.z, gamma, mode));
}

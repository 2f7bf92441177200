// The display's tone curve (shared by GLSL and C++: common/shading/shared_shading.hpp): exposed
// linear light -> linear display light, before the gamut map (gamut_map.glsl) and the encode.
//
// The curve is the extended Reinhard operator (Reinhard, Stark, Shirley and Ferwerda 2002, §3,
// eq. 4) on the luminance Y alone:
//     Y_d = Y (1 + Y / W^2) / (1 + Y)
// It is the identity's slope near black, rolls highlights off smoothly, and reaches exactly 1 at
// Y = W, the "white": the exposed luminance the master decides for the whole cluster once per
// frame (RenderSettings::tone_white), so every channel rolls off alike. The colour is scaled by
// Y_d / Y, which keeps its chromaticity; a component that the scaling leaves above 1 is then
// brought into the display's cube at constant luminance by the gamut map, toward white along the
// colour's own hue, never clipped per channel. W <= 0 means no curve (a fixed, calibration
// exposure): the colour is returned unchanged.

// Y: exposed luminance (>= 0); white: W (> 0).
float tone_curve_luminance(float y, float white) {
    return y * (1.0 + y / (white * white)) / (1.0 + y);
}

// The inverse on [0, 1): the Y whose displayed luminance is y_d (the root of
// Y^2 / W^2 + Y (1 - y_d) - y_d = 0 that is >= 0, in the form without cancellation).
float tone_curve_luminance_inverse(float y_d, float white) {
    float b = 1.0 - y_d;
    return 2.0 * y_d / (b + sqrt(b * b + 4.0 * y_d / (white * white)));
}

// c: exposed linear BT.709 RGB; white: the luminance shown as white (<= 0: none).
vec3 tone_curve(vec3 c, float white) {
    float y = rec709_luminance(c);
    if (!(white > 0.0) || !(y > 0.0)) return c;
    return c * (tone_curve_luminance(y, white) / y);
}

// The inverse of tone_curve for a displayed colour whose luminance is below 1.
vec3 tone_curve_inverse(vec3 c, float white) {
    float y_d = rec709_luminance(c);
    if (!(white > 0.0) || !(y_d > 0.0)) return c;
    return c * (tone_curve_luminance_inverse(min(y_d, 0.999999), white) / y_d);
}

// Night vision: how the eye sees colour as the light fails (shared by GLSL and C++: the warp pass
// and the PNG display transform), in linear light before the display curve.
//
// Two published parts:
// - How much of what the eye sees comes from the cones: the mesopic adaptation coefficient m of
//   the CIE system for mesopic photometry (CIE 191:2010, the MES2 model, section 3):
//       m = 0.7670 + 0.3334 log10(L_mes),  clamped to [0, 1],
//   which is 1 (photopic, the cones alone) at 5 cd/m^2 and above and 0 (scotopic, the rods alone)
//   at 0.005 cd/m^2 and below. The mesopic luminance L_mes is taken as the brighter of the eye's
//   adapted luminance (the master's, one value for the whole cluster) and the pixel's own: a point
//   of light bright enough drives the cones where it falls, which is why Betelgeuse is orange to
//   the naked eye in a dark sky. (CIE iterates L_mes from the photopic and scotopic luminances of
//   the adapting field; a grey field's are equal in its normalisation, which is what is used.)
// - What the rods see: the scotopic luminance of the colour, from its CIE XYZ by Larson,
//   Rushmeier and Piatko's (1997, section 4) fit, Y_s = Y (1.33 (1 + (Y + Z) / X) - 1.68),
//   scaled so that the D65 white keeps its luminance, and shown with the chromaticity
//   x = y = 0.25 that Jensen et al. (2000, section 6) give the rods' blue shift.
// The colour seen is m c + (1 - m) Y_rod blue: the colour fades and turns blue as m falls; a red
// darkens and a blue brightens (the Purkinje shift) because Y_rod weighs blue more than Y does.
// adapted_cd_m2 <= 0 means night vision is off: the colour is returned unchanged.

const float NIGHT_CONES_ALONE_CD_M2 = 5.0;     // m = 1 at and above
const float NIGHT_RODS_ALONE_CD_M2 = 0.005;    // m = 0 at and below
// Linear BT.709 RGB of chromaticity (0.25, 0.25) with luminance 1 (X = Y = 1, Z = 2 through the
// XYZ -> linear sRGB matrix of IEC 61966-2-1).
const vec3 NIGHT_ROD_BLUE = vec3(0.7062, 0.9899, 1.9657);
// Y_s / Y of the D65 white (X, Z = 0.9505, 1.0890, the rows of rod_luminance): 1.33 (1 + 2.0890 / 0.9505) - 1.68.
const float NIGHT_ROD_WHITE = 2.57306;

// CIE 191:2010's m for a mesopic luminance (cd/m^2).
float mesopic_cone_share(float l_mes_cd_m2) {
    if (!(l_mes_cd_m2 > NIGHT_RODS_ALONE_CD_M2)) return 0.0;
    return clamp(0.7670 + 0.3334 * log(l_mes_cd_m2) / log(10.0), 0.0, 1.0);
}

// The rods' luminance of a linear BT.709 colour, in units where the D65 white's equals its Y.
float rod_luminance(vec3 c) {
    float x = 0.4124 * c.r + 0.3576 * c.g + 0.1805 * c.b;
    float y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    float z = 0.0193 * c.r + 0.1192 * c.g + 0.9505 * c.b;
    if (!(x > 0.0) || !(y > 0.0)) return max(y, 0.0);
    return max(y * (1.33 * (1.0 + (y + z) / x) - 1.68), 0.0) / NIGHT_ROD_WHITE;
}

// c: exposed linear colour; exposure: what c was multiplied by (so c / exposure is cd/m^2 in a
// physical scene); adapted_cd_m2: the eye's adaptation (<= 0: off).
vec3 night_vision(vec3 c, float exposure, float adapted_cd_m2) {
    if (!(adapted_cd_m2 > 0.0) || !(exposure > 0.0)) return c;
    float own_cd_m2 = rec709_luminance(c) / exposure;
    float m = mesopic_cone_share(max(adapted_cd_m2, own_cd_m2));
    if (m >= 1.0) return c;
    return m * c + (1.0 - m) * rod_luminance(c) * NIGHT_ROD_BLUE;
}

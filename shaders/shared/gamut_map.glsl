// Out-of-gamut colours into the output gamut (shared by GLSL and C++: common/shading/shared_shading.hpp).
// Linear light in the ITU-R BT.709 primaries with the D65 white (the primaries and white of
// IEC 61966-2-1 sRGB), after exposure; the output gamut is the unit cube [0, 1]^3 of a display
// or a projector. docs/COLOR.md says why and where it is applied.
//
// The method: a colour outside the cube moves along the straight line toward the grey of its own
// luminance, (Y, Y, Y), to the first point inside the cube. Every point of that line has the
// luminance Y (the weights sum to 1) and, being an additive mixture of the colour and the white,
// a chromaticity on the line from the white point through the colour's chromaticity: the dominant
// wavelength is kept and only the excitation purity drops (CIE 015:2004 §9.1). It is gamut
// clipping that keeps the lightness and projects toward the neutral axis (Ottosson 2020, "sRGB
// gamut clipping": keep lightness constant, only compress chroma), done here in linear
// light with the luminance as the quantity kept, rather than clipping each channel, which shifts
// both hue and luminance (a negative blue clipped to 0 adds luminance). A luminance
// at or below 0 has no representable colour and maps to black, one at or above 1 to white.
// Colours inside the cube are returned unchanged.

// Relative luminance of linear BT.709 RGB (ITU-R BT.709-6 (2015) Part 1, item 3.2).
float rec709_luminance(vec3 c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// c: linear RGB, any value (NaN maps to black). Returns a colour in [0, 1]^3.
vec3 gamut_map_to_unit_cube(vec3 c) {
    float y = rec709_luminance(c);
    if (!(y > 0.0)) return vec3(0.0);
    if (y >= 1.0) return vec3(1.0);
    float lo = min(c.x, min(c.y, c.z));
    float hi = max(c.x, max(c.y, c.z));
    if (lo >= 0.0 && hi <= 1.0) return c;
    // The largest t in [0, 1] for which Y + t (c - Y) stays inside: lo and hi reach 0 and 1.
    float t = 1.0;
    if (lo < 0.0) t = min(t, y / (y - lo));
    if (hi > 1.0) t = min(t, (1.0 - y) / (hi - y));
    return clamp(vec3(y) + (c - vec3(y)) * t, 0.0, 1.0);  // the clamp only absorbs rounding
}

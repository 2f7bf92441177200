// The night sky's own light: airglow, zodiacal and scattered starlight, and light pollution, given
// as the sky brightness at the zenith (shared by GLSL and C++). A planetarium gives it as a
// surface brightness in V magnitudes per square arcsecond, or as a Bortle class
// (common/scene/night_sky.hpp turns either into cd/m^2; the master sends the zenith luminance in
// the snapshot, one value for the whole cluster).
//
// Toward the horizon the sky brightens as the airmass X grows, and the air in front dims it:
// Krisciunas and Schaefer (1991, equations 2 and 3) give the dark sky at zenith distance z as
//     B(z) = B_zenith X 10^(-0.4 k (X - 1)),   X = (1 - 0.96 sin^2 z)^(-1/2),
// with k the V-band extinction coefficient (0.172 at Mauna Kea in their paper; 0.2 here, a good
// low site). The same gradient is used for a light-polluted sky, whose glow is also scattered in
// the air along the line of sight. Above the ground the glow falls with the air over the camera
// (scale height 8 km): it is light scattered by the air and emitted high in it.

const float NIGHT_SKY_EXTINCTION_K = 0.2;    // V magnitudes per airmass
const float NIGHT_SKY_SCALE_HEIGHT_M = 8000.0;
// The glow's colours (linear BT.709, luminance 1). The natural night sky, up to its 22.0
// mag/arcsec^2, is airglow (the green oxygen line over a continuum) and starlight: chromaticity
// (0.30, 0.35). What a city adds above that has the colour of a 3500 K blackbody, chromaticity
// (0.4053, 0.3907), between sodium and white-LED street light.
const vec3 NIGHT_SKY_NATURAL_RGB = vec3(0.7419, 1.0868, 0.9007);
const vec3 NIGHT_SKY_CITY_RGB = vec3(1.5639, 0.8925, 0.4058);
const float NIGHT_SKY_NATURAL_CD_M2 = 1.7118e-4;  // 22.0 mag/arcsec^2

// Luminance (cd/m^2) of a surface brightness in V mag/arcsec^2: 1.08e5 x 10^(-0.4 m) (the zero
// point of the V band spread over one square arcsecond).
float night_sky_cd_m2_of_mag(float mag_arcsec2) { return 1.08e5 * exp2(-0.4 * 3.32192809 * mag_arcsec2); }

// B(z) / B_zenith for a direction whose zenith cosine is cos_z (0 at and below the horizon's
// airmass of 5.1, the formula's own limit at z = 90 degrees).
float night_sky_gradient(float cos_z) {
    float s2 = 1.0 - clamp(cos_z, 0.0, 1.0) * clamp(cos_z, 0.0, 1.0);
    float airmass = 1.0 / sqrt(1.0 - 0.96 * s2);
    return airmass * exp2(-0.4 * 3.32192809 * NIGHT_SKY_EXTINCTION_K * (airmass - 1.0));
}

// The glow's colour for a zenith luminance (cd/m^2): its natural part and the city's above it.
vec3 night_sky_rgb(float zenith_cd_m2) {
    float natural = min(zenith_cd_m2, NIGHT_SKY_NATURAL_CD_M2);
    return natural * NIGHT_SKY_NATURAL_RGB + max(zenith_cd_m2 - natural, 0.0) * NIGHT_SKY_CITY_RGB;
}

// The glow at the camera's height above the ground (metres): zenith luminance times the air left
// above it.
float night_sky_at_height(float zenith_cd_m2, float height_m) {
    return zenith_cd_m2 * exp(-max(height_m, 0.0) / NIGHT_SKY_SCALE_HEIGHT_M);
}

// The glow (cd/m^2) a camera height_m above the ground sees in a direction of zenith cosine cos_z.
float night_sky_luminance(float zenith_cd_m2, float height_m, float cos_z) {
    return night_sky_at_height(zenith_cd_m2, height_m) * night_sky_gradient(cos_z);
}

// Star colour from the B-V index (shared by GLSL and C++).
//  1. B-V -> effective temperature: Ballesteros (2012), EPL 97, 34008, eq. 14:
//       T = 4600 K * (1 / (0.92 (B-V) + 1.7) + 1 / (0.92 (B-V) + 0.62))
//  2. Planck spectrum -> CIE 1931 XYZ, with the multi-lobe Gaussian fits of the colour-matching
//     functions of Wyman, Sloan & Shirley (2013), JCGT 2(2), "Simple Analytic Approximations to
//     the CIE XYZ Color Matching Functions", integrated 380..780 nm in 5 nm steps.
//  3. XYZ -> linear sRGB (IEC 61966-2-1 matrix, D65), negative parts clipped, scaled so that
//     the luminance 0.2126 R + 0.7152 G + 0.0722 B is exactly 1.
float bv_to_temperature(float bv) {
    float b = clamp(bv, -0.4, 2.0);
    return 4600.0 * (1.0 / (0.92 * b + 1.7) + 1.0 / (0.92 * b + 0.62));
}

float cie_lobe(float x, float mu, float s1, float s2) {
    float s = x < mu ? s1 : s2;
    float t = (x - mu) / s;
    return exp(-0.5 * t * t);
}

// CIE 1931 2-degree colour-matching functions (x-bar, y-bar, z-bar) at lambda_nm.
vec3 cie_xyz_bar(float lambda_nm) {
    float xb = 1.056 * cie_lobe(lambda_nm, 599.8, 37.9, 31.0) + 0.362 * cie_lobe(lambda_nm, 442.0, 16.0, 26.7) -
               0.065 * cie_lobe(lambda_nm, 501.1, 20.4, 26.2);
    float yb = 0.821 * cie_lobe(lambda_nm, 568.8, 46.9, 40.5) + 0.286 * cie_lobe(lambda_nm, 530.9, 16.3, 31.1);
    float zb = 1.217 * cie_lobe(lambda_nm, 437.0, 11.8, 36.0) + 0.681 * cie_lobe(lambda_nm, 459.0, 26.0, 13.8);
    return vec3(xb, yb, zb);
}

// CIE XYZ -> linear sRGB (IEC 61966-2-1, D65).
vec3 xyz_to_linear_srgb(vec3 xyz) {
    return vec3(3.2406 * xyz.x - 1.5372 * xyz.y - 0.4986 * xyz.z, -0.9689 * xyz.x + 1.8758 * xyz.y + 0.0415 * xyz.z,
                0.0557 * xyz.x - 0.2040 * xyz.y + 1.0570 * xyz.z);
}

// Planck spectral radiance up to a constant factor; lambda in nanometres.
float planck_relative(float lambda_nm, float temperature_k) {
    float l = lambda_nm * 0.001;  // micrometres keep the powers in float range
    return 1.0 / (l * l * l * l * l * (exp(14387.77 / (l * temperature_k)) - 1.0));
}

vec3 blackbody_xyz(float temperature_k) {
    vec3 xyz = vec3(0.0, 0.0, 0.0);
    for (int i = 0; i <= 80; i++) {
        float lambda = 380.0 + 5.0 * float(i);
        float p = planck_relative(lambda, temperature_k);
        xyz = xyz + cie_xyz_bar(lambda) * p;
    }
    return xyz;
}

vec3 bv_to_linear_srgb(float bv) {
    vec3 xyz = blackbody_xyz(bv_to_temperature(bv));
    xyz = xyz / xyz.y;
    vec3 rgb = xyz_to_linear_srgb(xyz);
    rgb = max(rgb, 0.0);
    float lum = 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
    return rgb / lum;
}

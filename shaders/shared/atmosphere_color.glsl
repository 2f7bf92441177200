// From the production model's three (or six) sample wavelengths to colour (shared by GLSL and C++).
// The spectrum between the samples is rebuilt as a power law in wavelength -- log f linear in
// log lambda, piecewise through (440, 550, 680) nm and extrapolated with the end slopes -- which is
// exact for a pure Rayleigh sky (f ~ lambda^-4) where linear interpolation of f overestimates
// the red by ~10 %. `weights` is an n x 1 table whose texel k holds
// 683 * S(lambda_k) * (xbar, ybar, zbar)(lambda_k) * d lambda in xyz and lambda_k (nm) in w
// (S = solar spectral irradiance), built by production_color.cpp. f is per unit solar irradiance.
// The sample wavelengths (nm) of the production model's vec3 channels (x, y, z).
const float ATM_LAMBDA_R = 680.0;
const float ATM_LAMBDA_G = 550.0;
const float ATM_LAMBDA_B = 440.0;

vec3 atm_samples_to_xyz(vec3 f, sampler2D weights, float n) {
    if (max(f.x, max(f.y, f.z)) <= 0.0) return vec3(0.0);
    vec3 lf = log(max(f, 1e-30));
    float l_r = log(ATM_LAMBDA_R);
    float l_g = log(ATM_LAMBDA_G);
    float l_b = log(ATM_LAMBDA_B);
    vec3 xyz = vec3(0.0);
    int count = int(n);
    for (int k = 0; k < count; ++k) {
        vec4 w = textureLod(weights, vec2((float(k) + 0.5) / n, 0.5), 0.0);
        float x = log(w.w);
        float lv = (x < l_g) ? mix(lf.z, lf.y, (x - l_b) / (l_g - l_b)) : mix(lf.y, lf.x, (x - l_g) / (l_r - l_g));
        xyz = xyz + vec3(w) * exp(lv);
    }
    return xyz;
}

// The second sample triplet of the sky-view level (vec3 channels x, y, z), between the first's:
// with six samples, 400..680 nm, the log-log reconstruction follows the curvature of long
// extinguished paths (exp(-tau lambda^-4) is not a power law: the limb, twilight) and the ozone
// Chappuis band; three samples leave u'v' errors of ~0.01 there.
const float ATM_LAMBDA2_R = 610.0;
const float ATM_LAMBDA2_G = 500.0;
const float ATM_LAMBDA2_B = 400.0;

// The same from six samples: f at (680, 550, 440) nm, f2 at (610, 500, 400) nm; log f piecewise
// linear in log lambda through the six, extrapolated with the end slopes.
vec3 atm_samples6_to_xyz(vec3 f, vec3 f2, sampler2D weights, float n) {
    if (max(max(f.x, max(f.y, f.z)), max(f2.x, max(f2.y, f2.z))) <= 0.0) return vec3(0.0);
    vec3 lf = log(max(f, 1e-30));
    vec3 lf2 = log(max(f2, 1e-30));
    float l0 = log(ATM_LAMBDA2_B);
    float l1 = log(ATM_LAMBDA_B);
    float l2 = log(ATM_LAMBDA2_G);
    float l3 = log(ATM_LAMBDA_G);
    float l4 = log(ATM_LAMBDA2_R);
    float l5 = log(ATM_LAMBDA_R);
    vec3 xyz = vec3(0.0);
    int count = int(n);
    for (int k = 0; k < count; ++k) {
        vec4 w = textureLod(weights, vec2((float(k) + 0.5) / n, 0.5), 0.0);
        float x = log(w.w);
        float lv;
        if (x < l1) {
            lv = mix(lf2.z, lf.z, (x - l0) / (l1 - l0));
        } else if (x < l2) {
            lv = mix(lf.z, lf2.y, (x - l1) / (l2 - l1));
        } else if (x < l3) {
            lv = mix(lf2.y, lf.y, (x - l2) / (l3 - l2));
        } else if (x < l4) {
            lv = mix(lf.y, lf2.x, (x - l3) / (l4 - l3));
        } else {
            lv = mix(lf2.x, lf.x, (x - l4) / (l5 - l4));
        }
        xyz = xyz + vec3(w) * exp(lv);
    }
    return xyz;
}

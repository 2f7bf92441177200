// From the production model's three sample wavelengths to colour (shared by GLSL and C++).
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

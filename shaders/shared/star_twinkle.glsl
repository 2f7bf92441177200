// The stars' twinkling (shared by GLSL and C++: common/shading/shared_shading.hpp).
//
// Amplitude: the relative standard deviation of a star's intensity through an aperture of
// diameter D over an integration time t, under the air above an observer at height h (Young
// 1967's approximation, in the form of Osborn et al. 2015):
//     sigma^2 = 1e-5 D^(-4/3) t^(-1) X^3 exp(-2 h / H),  D in m, t in s, H = 8000 m,
// X the airmass (Kasten and Young 1989). For the eye, D = 7 mm (the dark-adapted pupil) and
// t = 0.1 s (its integration time): sigma = 0.27 at the zenith at sea level, rising as X^1.5
// toward the horizon. The relation is for weak scintillation; sigma is capped at
// TWINKLE_SIGMA_MAX, where the intensity's fluctuations saturate.
//
// Time: three sines of a few hertz per star, their frequencies and phases from a hash of the
// star's index, so that the twinkling is a deterministic function of (star, twinkle clock): every
// channel computes the same factor for the same star in the same frame. The factor is
// exp(s n - s^2 / 2) with n of unit variance and s^2 = ln(1 + sigma^2): never negative, of mean
// about 1 and relative deviation about sigma.

const float TWINKLE_PUPIL_M = 0.007;
const float TWINKLE_EYE_TIME_S = 0.1;
const float TWINKLE_SCALE_HEIGHT_M = 8000.0;
const float TWINKLE_SIGMA_MAX = 1.0;

// Kasten and Young (1989): the relative optical airmass at a zenith cosine (below the horizon:
// the horizon's, 38).
float twinkle_airmass(float cos_zenith) {
    float z_deg = acos(clamp(cos_zenith, 0.0, 1.0)) * 57.2957795131;
    return 1.0 / (max(cos_zenith, 0.0) + 0.50572 * pow(96.07995 - z_deg, -1.6364));
}

// The relative deviation at the zenith for an observer at height_m (>= 0).
float twinkle_sigma_zenith(float height_m) {
    float d43 = pow(TWINKLE_PUPIL_M, -4.0 / 3.0);
    return sqrt(1e-5 * d43 / TWINKLE_EYE_TIME_S) * exp(-max(height_m, 0.0) / TWINKLE_SCALE_HEIGHT_M);
}

// The relative deviation at airmass X, from the zenith's.
float twinkle_sigma(float sigma_zenith, float airmass) {
    return min(sigma_zenith * pow(airmass, 1.5), TWINKLE_SIGMA_MAX);
}

// An integer hash of 32 bits (the "lowbias32" constants of Chris Wellons' hash prospector).
uint twinkle_hash(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// A number in [0, 1) from a star's index and a stream.
float twinkle_uniform(uint star, uint stream) {
    return float(twinkle_hash(star * 8u + stream) >> 8u) / 16777216.0;
}

// Zero mean, unit variance over time: three sines of 2.3, 5.9 and 11.7 Hz, each +-20 % per star.
float twinkle_noise(uint star, float t_s) {
    float n = 0.0;
    for (int k = 0; k < 3; ++k) {
        float base_hz = k == 0 ? 2.3 : (k == 1 ? 5.9 : 11.7);
        float f_hz = base_hz * (0.8 + 0.4 * twinkle_uniform(star, uint(2 * k)));
        float phase = 6.28318530718 * twinkle_uniform(star, uint(2 * k + 1));
        n += sin(6.28318530718 * f_hz * t_s + phase);
    }
    return n * 0.81649658;  // sqrt(2 / 3): each sine has variance 1/2
}

// The factor on a star's intensity (1 when sigma is 0).
float twinkle_factor(uint star, float t_s, float sigma) {
    if (!(sigma > 0.0)) return 1.0;
    float s2 = log(1.0 + sigma * sigma);
    return exp(sqrt(s2) * twinkle_noise(star, t_s) - 0.5 * s2);
}

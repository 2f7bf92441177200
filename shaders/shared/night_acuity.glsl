// The eye's acuity at night: how much detail the dark-adapted eye resolves, as a Gaussian blur of
// the displayed sky in dome angles (shared by GLSL and C++: the warp pass and the domemaster's PNG
// display transform), applied to linear light before night vision and the display curve.
//
// - The finest grating the eye resolves at an adaptation luminance L (cd/m^2), in cycles per
//   degree, is Ferwerda, Pattanaik, Shirley and Greenberg's (1996, the section on visual acuity)
//   fit to Shlaer's (1937) measurements:
//       R(L) = 17.25 atan(1.4 log10(L) + 0.35) + 25.72,
//   about 47 cycles/degree at 100 cd/m^2, 31 at 1 and 3 at 0.001 cd/m^2.
// - The blur is the Gaussian that halves the contrast of that grating: its transfer function is
//   exp(-2 pi^2 sigma^2 f^2), one half at f = R when sigma = sqrt(ln 2 / 2) / (pi R). At
//   0.001 cd/m^2 that is 0.063 degrees (0.7 px of a 2048 px domemaster), at 0.1 cd/m^2 0.016
//   degrees; the display transforms skip it where it is under a quarter of a pixel.
// - The blur is taken with 13 taps in angle around the pixel's direction, so that its width is
//   the same on every channel and in the domemaster whatever their pixel densities: a centre tap
//   and two rings of six. Each stands for one zone of the 2-D Gaussian (radius < 0.8 sigma,
//   0.8 to 2 sigma, beyond 2 sigma) and carries its probability; the ring radii are the zones'
//   root-mean-square radii, scaled by 1.0216 so that the taps' variance is the Gaussian's
//   (sigma^2 along every axis; a six-fold ring is isotropic in its second moments).
// adapted_cd_m2 <= 0 means night vision is off: no blur.

const float ACUITY_CENTRE_WEIGHT = 0.2738510;  // P(r < 0.8 sigma)
const float ACUITY_RING1_WEIGHT = 0.5908138;   // P(0.8 sigma < r < 2 sigma), shared by six taps
const float ACUITY_RING2_WEIGHT = 0.1353353;   // P(r > 2 sigma)
const float ACUITY_RING1_RADIUS = 1.3968838;   // in sigma
const float ACUITY_RING2_RADIUS = 2.5019336;
const int ACUITY_TAPS = 13;

// The finest resolved grating at adaptation luminance adapted_cd_m2, cycles per degree.
float acuity_cycles_per_deg(float adapted_cd_m2) {
    float log_l = log(max(adapted_cd_m2, 1e-9)) / log(10.0);
    return 17.25 * atan(1.4 * log_l + 0.35) + 25.72;
}

// The acuity blur's standard deviation (radians) at an adaptation luminance; 0 when off.
float acuity_blur_sigma_rad(float adapted_cd_m2) {
    if (!(adapted_cd_m2 > 0.0)) return 0.0;
    float cycles_per_rad = acuity_cycles_per_deg(adapted_cd_m2) * (180.0 / CUPOLA_PI);
    return sqrt(0.5 * log(2.0)) / (CUPOLA_PI * max(cycles_per_rad, 1e-3));
}

// Tap k (0 .. ACUITY_TAPS - 1): (x, y, weight), its offset in units of sigma in the plane
// tangent to the sky at the pixel's direction.
vec3 acuity_tap(int k) {
    if (k == 0) return vec3(0.0, 0.0, ACUITY_CENTRE_WEIGHT);
    bool inner = k <= 6;
    float angle_rad = float(k - 1) * (CUPOLA_PI / 3.0) + (inner ? 0.0 : CUPOLA_PI / 6.0);
    float r = inner ? ACUITY_RING1_RADIUS : ACUITY_RING2_RADIUS;
    float w = (inner ? ACUITY_RING1_WEIGHT : ACUITY_RING2_WEIGHT) / 6.0;
    return vec3(r * cos(angle_rad), r * sin(angle_rad), w);
}

// The direction of tap k around the unit direction d, for a blur of sigma_rad: the tap's offset
// is an arc on the sky, in the tangent plane spanned by a fixed pair of axes (x first; z where d
// is along x).
vec3 acuity_tap_direction(vec3 d, float sigma_rad, int k) {
    vec3 t = acuity_tap(k);
    vec3 ref = abs(d.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 0.0, 1.0);
    vec3 e1 = normalize(ref - d * dot(d, ref));
    vec3 e2 = cross(d, e1);
    vec2 arc_rad = vec2(t.x, t.y) * sigma_rad;
    float r_rad = length(arc_rad);
    if (!(r_rad > 0.0)) return d;
    vec2 along = arc_rad / r_rad;
    return d * cos(r_rad) + (e1 * along.x + e2 * along.y) * sin(r_rad);
}

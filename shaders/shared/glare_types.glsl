// Plain data types of the shared glare code (shared by GLSL and C++; see atmosphere_types.glsl
// for why types live apart from the functions). The functions are in glare_psf.glsl.

// The look of the eye's glare around a bright source (the Sun). All angles are radians on the
// sky, cluster-wide (never pixels), so every channel draws the same glare.
//
// Recommended defaults:
//   strength         1        Spencer et al.'s average eye
//   extent_rad       60 deg   (1.0471976) the bloom term still holds ~5 % of its energy beyond,
//                             see glare_psf.glsl; the fade keeps the cost bounded
//   halo_radius_rad  3.5 deg  (0.0610865) a DESIGN value, not from Spencer's formula (which has
//                             no ring): the lenticular halo seen around bright lights is a few
//                             degrees across
//   halo_width_rad   0.35 deg (0.0061087) design value too
//   halo_fraction    0.15
//   streak_count     96
//   streak_contrast  0.6
//   phase            animation time in whatever unit the master advances (ray flicker runs at
//                    0.05 - 0.2 cycles per unit); keep it within ~1e4 so float keeps its fraction
struct GlareParams {
    float strength;         // multiplies the physical PSF (1 = Spencer's eye)
    float extent_rad;       // nothing beyond this angle from the centre (< pi/2); smooth fade over the last 15 %
    float halo_radius_rad;  // lenticular halo ring radius at the green sample (550 nm)
    float halo_width_rad;   // Gaussian sigma of the ring
    float halo_fraction;    // share of the flare term's energy moved into the ring (0..1)
    float streak_count;     // ciliary-corona rays around the circle (even integer as float)
    float streak_contrast;  // 0: no rays, 1: all flare energy in the rays
    float phase;            // animation phase (the master puts it in the snapshot; all channels equal)
};

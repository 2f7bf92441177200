#pragma once
// The fixed list of sky queries on which every atmosphere model is validated against the CPU
// reference (data/atmosphere/<body>_reference.csv is the reference evaluated on exactly this list).
//
// CONSTRUCTION (deterministic: no RNG, only a golden-ratio sequence, so the list never changes
// unless this file does). For each camera, in this order,
//   "ground"  altitude kMinCameraAltitude (the integrator raises lower cameras to it)
//   "10km"    altitude 10 km
//   "100km"   altitude 100 km
//   "1000km"  altitude 1000 km
//   "limb"    altitude 400 km, looking at the planet's rim
// and for each sun zenith in {30, 65, 88, 95} degrees, there are `directions_per_set` view
// directions i = 0..N-1 (N = directions_per_set). Each direction set is a spherical-Fibonacci
// lattice on a band of zenith cosines [mu_lo, mu_hi]:
//   mu_i  = mu_hi - (mu_hi - mu_lo) (i + 1/2) / N        (uniform in solid angle over the band)
//   phi_i = 360 deg * frac(i / golden_ratio), mapped to [-180, 180)   (relative azimuth)
// The half-step offset keeps every mu_i strictly inside the band (never exactly on its edges).
// The band depends on the camera radius r = bottom_radius + altitude:
//   * camera inside the atmosphere (r <= top_radius; ground and 10 km for the presets): the full
//     sphere, mu in [-1, 1];
//   * camera outside (100 km, 1000 km for the presets): the cap of directions whose ray meets the
//     top sphere, mu in [-1, -sqrt(1 - (top/r)^2)], i.e. view zenith from 180 - asin(top/r) to 180
//     deg; near-tangent rays are kept;
//   * limb: from 2 deg below the ground horizon (view zenith 180 - asin(bottom/r) + 2 deg, rays that
//     hit the ground close to the rim) up to the ray tangent to the top sphere (view zenith
//     180 - asin(top/r)), so the band covers the glowing rim seen from orbit. The limb camera must
//     be outside the atmosphere (std::invalid_argument otherwise).
// Sizes: 5 cameras x 4 suns x N cases, camera-major, then sun, then direction.
#include <string>
#include <vector>

#include "atmosphere/atmosphere_parameters.hpp"
#include "atmosphere/reference_integrator.hpp"

namespace cupola::atmosphere {

struct ValidationCase {
    std::string camera;  // "ground", "10km", "100km", "1000km" or "limb"
    SkyQuery query;
};

// The camera names in list order, and the sun zenith angles (deg) of every camera.
const std::vector<std::string>& validation_cameras();
const std::vector<double>& validation_sun_zeniths_deg();
// Camera altitude (m) for a name of validation_cameras(); std::invalid_argument for others.
double validation_camera_altitude(const std::string& camera);

std::vector<ValidationCase> validation_set(const AtmosphereParameters& p, int directions_per_set = 512);

}  // namespace cupola::atmosphere

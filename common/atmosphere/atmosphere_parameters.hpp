#pragma once
// Physical description of a planetary atmosphere for the reference integrator (and, later, for
// the GPU models that are measured against it). Everything is in SI units: lengths in metres,
// coefficients in m^-1, wavelengths in nanometres, solar spectral irradiance in W m^-2 nm^-1.
//
// Species (all optional, each with its own density profile in [0, 1]):
//   Rayleigh  scattering only, beta_R(lambda) = rayleigh_scattering_at_1um * (lambda/1um)^-rayleigh_exponent,
//             density exp(-h / rayleigh_scale_height); phase 3/(16 pi) (1 + nu^2).
//   Mie       extinction beta_M,ext(lambda) = mie_extinction_at_550nm * (lambda/550nm)^-mie_angstrom_alpha,
//             scattering = extinction * mie_single_scattering_albedo(lambda),
//             density exp(-h / mie_scale_height); Cornette-Shanks phase with mie_g.
//   Ozone     absorption only, beta_O(lambda) = ozone_peak_number_density() * ozone_cross_section(lambda),
//             tent density 0 below ozone_bottom, 1 at ozone_peak, 0 above ozone_top (linear between).
// A scale height of +infinity gives a uniform density (used by the closed-form toy tests).
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace cupola::atmosphere {

// A spectral quantity given by (wavelength nm, value) anchors, linearly interpolated and held
// constant outside the anchor range. A single anchor is a constant.
struct SpectralCurve {
    std::vector<std::pair<double, double>> anchors;  // sorted by wavelength

    static SpectralCurve constant(double value) { return SpectralCurve{{{550.0, value}}}; }
    double operator()(double lambda_nm) const;
};

// Spectral irradiance (W m^-2 nm^-1) of a black body of temperature_k and radius radius_m seen
// from distance_m: pi * B_lambda(T) * (radius / distance)^2.
double blackbody_irradiance(double lambda_nm, double temperature_k, double radius_m, double distance_m);

struct AtmosphereParameters {
    std::string name;
    double bottom_radius = 6360000.0;  // m, the ground
    double top_radius = 6420000.0;     // m, the end of the atmosphere (density treated as 0 above)

    double rayleigh_scattering_at_1um = 1.24062e-6;  // m^-1 at lambda = 1 um
    double rayleigh_exponent = 4.0;
    double rayleigh_scale_height = 8000.0;  // m

    double mie_extinction_at_550nm = 4.44e-6;  // m^-1 at the ground
    double mie_angstrom_alpha = 0.0;
    double mie_scale_height = 1200.0;  // m
    double mie_g = 0.8;                // Cornette-Shanks asymmetry
    SpectralCurve mie_single_scattering_albedo = SpectralCurve::constant(0.9);

    double ozone_column_dobson = 300.0;                                // DU (1 DU = 2.687e20 molecules m^-2)
    double ozone_bottom = 10000.0;                                     // m, tent profile start
    double ozone_peak = 25000.0;                                       // m
    double ozone_top = 40000.0;                                        // m
    SpectralCurve ozone_cross_section = SpectralCurve::constant(0.0);  // m^2 per molecule

    SpectralCurve ground_albedo = SpectralCurve::constant(0.1);     // Lambertian
    SpectralCurve solar_irradiance = SpectralCurve::constant(1.0);  // W m^-2 nm^-1 at the planet

    // Derived per-wavelength coefficients (m^-1 at density 1).
    double rayleigh_scattering(double lambda_nm) const;
    double mie_extinction(double lambda_nm) const;
    double mie_scattering(double lambda_nm) const;
    double ozone_absorption(double lambda_nm) const;
    // Number density (m^-3) at the tent peak that puts ozone_column_dobson in the column.
    double ozone_peak_number_density() const;

    // Density profiles in [0, 1] at altitude h (m above bottom_radius).
    double rayleigh_density(double h) const;
    double mie_density(double h) const;
    double ozone_density(double h) const;

    // BLAKE2b-256 (libsodium crypto_generichash) of a canonical little-endian encoding of every
    // field (doubles as IEEE-754 bit patterns, vectors with their lengths, a format version tag).
    std::array<std::uint8_t, 32> hash() const;
    std::string hash_hex() const;

    // Earth after Bruneton 2017 / Hillaire 2020 (see the .cpp for every number's source).
    static AtmosphereParameters earth();
    // Mars: engineering preset (see the .cpp).
    static AtmosphereParameters mars();
};

}  // namespace cupola::atmosphere

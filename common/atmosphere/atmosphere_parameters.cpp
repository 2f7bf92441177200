#include "atmosphere/atmosphere_parameters.hpp"

#include <sodium.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace cupola::atmosphere {
namespace {

constexpr double kDobsonUnit = 2.687e20;  // molecules m^-2

// IAU 2015 nominal solar values (Resolution B3): radius 695 700 km, effective temperature 5772 K.
constexpr double kSunRadius = 6.957e8;
constexpr double kSunTemperature = 5772.0;
constexpr double kAstronomicalUnit = 1.495978707e11;  // IAU 2012 Resolution B2

// The solar spectrum as a black body sampled every 5 nm over 300..900 nm (linear interpolation
// between samples differs from the curve by < 0.1 %). Documented simplification: the real
// top-of-atmosphere spectrum (ASTM G-173 ETR) has Fraunhofer structure and is ~5-10 % higher
// than the 5772 K black body at 450-500 nm; the integrated visible colour is within a few %.
SpectralCurve blackbody_sun(double distance_m) {
    SpectralCurve c;
    for (double l = 300.0; l <= 900.0 + 1e-9; l += 5.0)
        c.anchors.emplace_back(l, blackbody_irradiance(l, kSunTemperature, kSunRadius, distance_m));
    return c;
}

class Encoder {
public:
    void tag(const char* s) {
        for (const char* p = s; *p; ++p) bytes_.push_back(static_cast<std::uint8_t>(*p));
        bytes_.push_back(0);
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    void f64(double v) {
        if (v == 0.0) v = 0.0;  // -0 and +0 hash alike
        u64(std::bit_cast<std::uint64_t>(v));
    }
    void curve(const char* name, const SpectralCurve& c) {
        tag(name);
        u64(c.anchors.size());
        for (const auto& [l, v] : c.anchors) {
            f64(l);
            f64(v);
        }
    }
    const std::vector<std::uint8_t>& bytes() const { return bytes_; }

private:
    std::vector<std::uint8_t> bytes_;
};

}  // namespace

double SpectralCurve::operator()(double lambda_nm) const {
    if (anchors.empty()) return 0.0;
    if (lambda_nm <= anchors.front().first) return anchors.front().second;
    if (lambda_nm >= anchors.back().first) return anchors.back().second;
    const auto it = std::upper_bound(anchors.begin(), anchors.end(), lambda_nm,
                                     [](double l, const std::pair<double, double>& a) { return l < a.first; });
    const auto& [l1, v1] = *it;
    const auto& [l0, v0] = *(it - 1);
    const double t = (lambda_nm - l0) / (l1 - l0);
    return v0 + (v1 - v0) * t;
}

double blackbody_irradiance(double lambda_nm, double temperature_k, double radius_m, double distance_m) {
    constexpr double h = 6.62607015e-34, c = 299792458.0, k = 1.380649e-23;  // SI 2019, exact
    const double l = lambda_nm * 1e-9;
    const double radiance = 2.0 * h * c * c / (l * l * l * l * l) / std::expm1(h * c / (l * k * temperature_k));
    const double ratio = radius_m / distance_m;
    return std::numbers::pi * radiance * ratio * ratio * 1e-9;  // per m -> per nm
}

double AtmosphereParameters::rayleigh_scattering(double lambda_nm) const {
    return rayleigh_scattering_at_1um * std::pow(lambda_nm / 1000.0, -rayleigh_exponent);
}
double AtmosphereParameters::mie_extinction(double lambda_nm) const {
    return mie_extinction_at_550nm * std::pow(lambda_nm / 550.0, -mie_angstrom_alpha);
}
double AtmosphereParameters::mie_scattering(double lambda_nm) const {
    return mie_extinction(lambda_nm) * mie_single_scattering_albedo(lambda_nm);
}
double AtmosphereParameters::ozone_peak_number_density() const {
    // The tent integrates to 0.5 * (ozone_top - ozone_bottom) times its peak.
    const double width = 0.5 * (ozone_top - ozone_bottom);
    return width > 0.0 ? ozone_column_dobson * kDobsonUnit / width : 0.0;
}
double AtmosphereParameters::ozone_absorption(double lambda_nm) const {
    return ozone_peak_number_density() * ozone_cross_section(lambda_nm);
}

double AtmosphereParameters::rayleigh_density(double h) const {
    return std::exp(-std::max(h, 0.0) / rayleigh_scale_height);
}
double AtmosphereParameters::mie_density(double h) const { return std::exp(-std::max(h, 0.0) / mie_scale_height); }
double AtmosphereParameters::ozone_density(double h) const {
    if (h <= ozone_bottom || h >= ozone_top) return 0.0;
    if (h <= ozone_peak) return (h - ozone_bottom) / (ozone_peak - ozone_bottom);
    return (ozone_top - h) / (ozone_top - ozone_peak);
}

std::array<std::uint8_t, 32> AtmosphereParameters::hash() const {
    if (sodium_init() < 0) throw std::runtime_error("libsodium initialisation failed");
    Encoder e;
    e.tag("cupola.atmosphere.v1");
    e.tag("radii");
    e.f64(bottom_radius);
    e.f64(top_radius);
    e.tag("rayleigh");
    e.f64(rayleigh_scattering_at_1um);
    e.f64(rayleigh_exponent);
    e.f64(rayleigh_scale_height);
    e.tag("mie");
    e.f64(mie_extinction_at_550nm);
    e.f64(mie_angstrom_alpha);
    e.f64(mie_scale_height);
    e.f64(mie_g);
    e.curve("mie_albedo", mie_single_scattering_albedo);
    e.tag("ozone");
    e.f64(ozone_column_dobson);
    e.f64(ozone_bottom);
    e.f64(ozone_peak);
    e.f64(ozone_top);
    e.curve("ozone_cross_section", ozone_cross_section);
    e.curve("ground_albedo", ground_albedo);
    e.curve("solar_irradiance", solar_irradiance);
    // The name is a label, not physics: it is deliberately not hashed.
    std::array<std::uint8_t, 32> out{};
    crypto_generichash(out.data(), out.size(), e.bytes().data(), e.bytes().size(), nullptr, 0);
    return out;
}

std::string AtmosphereParameters::hash_hex() const {
    const auto h = hash();
    std::string s;
    char buf[3];
    for (auto b : h) {
        std::snprintf(buf, sizeof buf, "%02x", b);
        s += buf;
    }
    return s;
}

AtmosphereParameters AtmosphereParameters::earth() {
    AtmosphereParameters p;
    p.name = "earth";
    // Radii, Rayleigh (1.24062e-6 lambda_um^-4, H 8 km), Mie (extinction 4.44e-6 = 5.328e-3 / 1200,
    // alpha 0, albedo 0.9, g 0.8 Cornette-Shanks, H 1.2 km), ozone 300 DU in a 10-25-40 km tent,
    // ground albedo 0.1: the constants of Bruneton 2017's demo (demo.cc; docs/REFERENCES.md).
    // Top at 60 km as Bruneton (Hillaire 2020 uses 100 km; above 60 km the Rayleigh density is < 6e-4).
    p.bottom_radius = 6360000.0;
    p.top_radius = 6420000.0;
    p.rayleigh_scattering_at_1um = 1.24062e-6;
    p.rayleigh_exponent = 4.0;
    p.rayleigh_scale_height = 8000.0;
    p.mie_extinction_at_550nm = 4.44e-6;
    p.mie_angstrom_alpha = 0.0;
    p.mie_scale_height = 1200.0;
    p.mie_g = 0.8;
    p.mie_single_scattering_albedo = SpectralCurve::constant(0.9);
    p.ozone_column_dobson = 300.0;
    p.ozone_bottom = 10000.0;
    p.ozone_peak = 25000.0;
    p.ozone_top = 40000.0;
    // Ozone cross sections (m^2). The anchors at 440/550/680 nm are Hillaire 2020's RGB ozone
    // absorption (8.5e-8, 1.881e-6, 6.5e-7 m^-1) divided by the 300 DU peak density, so those three
    // wavelengths reproduce Hillaire exactly. The other anchors only sketch the Chappuis band
    // (maximum ~5e-25 m^2 near 600 nm, Huggins tail below 400 nm); they are approximate (tens of
    // per cent) and an engineering choice: replace with a measured 293 K table (e.g. Serdyuchenko
    // et al. 2014) when ozone colour matters at those wavelengths.
    const double n = p.ozone_peak_number_density();
    p.ozone_cross_section.anchors = {{360.0, 1.0e-27},      {400.0, 1.5e-27}, {440.0, 8.5e-8 / n}, {500.0, 1.5e-25},
                                     {550.0, 1.881e-6 / n}, {600.0, 5.0e-25}, {640.0, 3.2e-25},    {680.0, 6.5e-7 / n},
                                     {730.0, 5.0e-26},      {780.0, 2.5e-26}, {830.0, 1.0e-26}};
    p.ground_albedo = SpectralCurve::constant(0.1);
    p.solar_irradiance = blackbody_sun(kAstronomicalUnit);
    return p;
}

AtmosphereParameters AtmosphereParameters::mars() {
    AtmosphereParameters p;
    p.name = "mars";
    // Mean radius 3389.5 km (IAU WGCCRE 2015); top 80 km above it (engineering choice: 7 scale heights).
    p.bottom_radius = 3389500.0;
    p.top_radius = 3389500.0 + 80000.0;
    // CO2 Rayleigh: Earth's sea-level coefficient scaled by the number-density ratio (Mars surface
    // ~610 Pa at ~210 K -> 2.10e23 m^-3 vs 2.545e25 m^-3 for Earth's 1.24062e-6 fit) and by the CO2/air
    // cross-section ratio ~2.45 (Sneep & Ubachs 2005, at 532 nm): 1.24062e-6 * 0.00825 * 2.45 = 2.51e-8.
    // Scale height 11.1 km (R T / (M g) with T 210 K, M 0.044 kg/mol, g 3.71 m/s^2).
    p.rayleigh_scattering_at_1um = 2.51e-8;
    p.rayleigh_exponent = 4.0;
    p.rayleigh_scale_height = 11100.0;
    // Dust ("Mie"): visible optical depth 0.5 (typical clear-season value; 0.3-1 outside storms)
    // spread over an 11 km scale height -> 0.5 / 11000 m^-1 at the ground; flat spectrum (alpha 0,
    // micron-sized grains); g 0.65 and a single-scattering albedo falling toward the blue (the
    // reddish colour), approximating the ranges reported by Tomasko et al. 1999 and Wolff et al.
    // 2009 -- an engineering choice, not a fit.
    p.mie_extinction_at_550nm = 0.5 / 11000.0;
    p.mie_angstrom_alpha = 0.0;
    p.mie_scale_height = 11000.0;
    p.mie_g = 0.65;
    p.mie_single_scattering_albedo.anchors = {{400.0, 0.75}, {450.0, 0.84},  {500.0, 0.89}, {550.0, 0.93},
                                              {600.0, 0.96}, {700.0, 0.975}, {800.0, 0.98}};
    // No ozone (Mars' column is < 0.1 % of Earth's).
    p.ozone_column_dobson = 0.0;
    p.ozone_cross_section = SpectralCurve::constant(0.0);
    // Reddish regolith, engineering choice (bright regions ~0.3 in the red, ~0.1 in the blue).
    p.ground_albedo.anchors = {{400.0, 0.08}, {500.0, 0.12}, {600.0, 0.25}, {700.0, 0.32}};
    // Same black-body Sun at Mars' mean distance 1.5237 AU.
    p.solar_irradiance = blackbody_sun(1.5237 * kAstronomicalUnit);
    return p;
}

}  // namespace cupola::atmosphere

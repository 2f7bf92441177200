#pragma once
// CPU reference integrator for sky radiance in a spherical-shell atmosphere, spectral and in
// double precision. Every later (GPU / table) atmosphere model is measured against it.
//
// UNITS. The solar spectral irradiance of AtmosphereParameters is in W m^-2 nm^-1 (the presets use
// a 5772 K black body at the planet's distance), so spectra returned here are spectral radiance in
// W m^-2 sr^-1 nm^-1, `luminance` is in cd m^-2 (683 lm/W * integral of L ybar), and `rgb` is linear
// sRGB (D65) scaled so its luminance 0.2126 R + 0.7152 G + 0.0722 B equals `luminance`. The Sun is a
// point source at infinity (its disc is not part of the sky radiance and it is not limb darkened);
// no refraction, no polarisation.
//
// METHOD.
//  * Optical depth: column densities of the three species (Rayleigh, Mie, ozone) are integrated
//    along rays with composite 5-point Gauss-Legendre panels; the ray is split exactly where it
//    crosses the kinks of the ozone tent and at its point of closest approach, and panel lengths
//    are chosen so that each panel spans at most ~panel_height_m of altitude (growing with
//    altitude). Per-wavelength optical depths are linear combinations of the three columns.
//  * Order 1 (deterministic): single scattering by the same quadrature along the view ray (split in
//    addition where the ray crosses the boundary of the planet's shadow cylinder, so the sunlit /
//    shadowed discontinuity never falls inside a panel), with the transmittance toward the Sun
//    integrated at every node; plus direct sunlight reflected by a Lambertian ground where the view
//    ray hits it.
//  * Orders 2..N (Monte Carlo): path tracing in the spherical shell with next-event estimation
//    toward the Sun, spectral (all wavelengths carried by every path). Why this method: it is
//    unbiased for the exact model (no angular or spatial table, so no discretisation error of
//    the kind the tested table-based models have -- a grid iteration would share their failure
//    modes: the horizon split, interpolation in mu_s/nu, coarse orders), it handles every geometry
//    (cameras in space, grazing rays, twilight, ground reflections of any order) with the same
//    code, and its error is statistical and self-reported: each query returns the standard error
//    of its multiple-scattering estimate, so tests can bound it. Details:
//      - free-flight distances are sampled from the balance-heuristic mixture over all wavelengths
//        of exp(-tau) sigma_t (hero wavelength chosen uniformly; the weight uses the mixture pdf),
//        so no wavelength's variance blows up where the extinction differs strongly (blue vs red
//        along the horizon);
//      - collisions are forced on segments that leave the atmosphere (no wasted escaping paths);
//        on segments that end on the ground, ground vs medium is chosen with probability equal to
//        the mean transmittance clamped to [0.05, 0.95] (no rare-event branch: a camera 1 m above
//        the ground looking down still samples the 1 m of air), the medium branch forced inside;
//      - directions at volume vertices are sampled from a mixture of the Rayleigh phase function
//        (exact inversion) and a Henyey-Greenstein lobe with the Mie g; Cornette-Shanks is
//        evaluated exactly in the weight (CS/HG <= 1.5, so weights stay bounded); ground vertices
//        sample the cosine lobe;
//      - sunlight is collected by next-event estimation (NEE) toward the Sun. With the default
//        MsEstimator::kLitSegment it is a line sample: on every segment of the path (the view ray
//        first), one extra distance is drawn for the NEE alone, independent of the collision that
//        continues the path, from a piecewise-constant density over the segment's quadrature
//        panels proportional to a cheap bound of the in-scattered sunlight (density x
//        transmittance along the segment at one wavelength x a tabulated luminance-weighted
//        transmittance toward the Sun, 0 in the planet's shadow, the larger of each panel's two
//        ends, plus a small floor so that every panel can be drawn). The estimate stays unbiased
//        (the density is positive wherever sunlight can be scattered, and the integrand is
//        evaluated exactly) and in twilight puts its samples in the high sunlit air instead of
//        the dense shadowed air where the collisions fall (Kulla & Fajardo 2012, sections 3-4:
//        sampling the distance for direct lighting separately from the path continuation).
//        At vertices in the planet's shadow, new directions are drawn from a mixture of the
//        phase function (or cosine lobe) and a lobe toward the nearest sunlit air (the twilight
//        arch), with the mixture's density in the weight (Veach 1997, section 9.2).
//        MsEstimator::kCollision is the plain estimator (NEE at the collision vertices), kept to
//        check the line sample against it;
//      - NEE of order 1 is skipped (computed deterministically above), unless ms_first_order = 1
//        (validation mode); segment k carries order k;
//      - adaptive path count (ms_max_paths > ms_paths): after ms_paths paths the count doubles
//        until the standard error of the luminance is at most ms_target_noise of the whole
//        luminance (order 1 included; of ms_target_floor where that is larger, so that skies too
//        dark to matter do not run to the cap) or ms_max_paths is reached; path i always uses stream i, so
//        the result is still a deterministic function of the query and the settings;
//      - each path has its own xoshiro256** stream seeded from (seed, path index): results are
//        deterministic for a fixed seed and independent of any future parallel split.
//  "Order" counts interactions: volume scattering events and ground reflections alike.
//
// COST (one core, -O2, 48 wavelengths): order 1 alone ~2 ms per sky(); with 4 orders and 4096
// paths ~100 ms, the multiple-scattering standard error then ~1.5-3 % of the order >= 2 part
// (~0.3-0.5 % of the total luminance) for daylight views; twilight views are noisier (figures for
// both estimators in data/atmosphere/PROVENANCE.md).
//
// LIMITS. A view ray exactly tangent to the top sphere from a camera exactly on it has a length set
// by rounding (~0.1 m); its (~1e-6 cd m^-2) value is finite but not meaningful. The Sun's disc is not
// resolved (point source), so the near-Sun aureole is that of a point source.
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "atmosphere/atmosphere_parameters.hpp"
#include "atmosphere/spectral_color.hpp"

namespace cupola::atmosphere {

// Rayleigh phase function 3/(16 pi) (1 + nu^2), per steradian, nu = cos(scattering angle).
double rayleigh_phase(double nu);
// Cornette-Shanks 1992: 3/(8 pi) (1 - g^2)(1 + nu^2) / ((2 + g^2)(1 + g^2 - 2 g nu)^(3/2)).
// Normalised to 1 over the sphere for every |g| < 1 (the (2 + g^2) factor does it).
double cornette_shanks_phase(double g, double nu);
// Henyey-Greenstein (1 - g^2) / (4 pi (1 + g^2 - 2 g nu)^(3/2)).
double henyey_greenstein_phase(double g, double nu);

// 360..830 nm in 10 nm steps (48 wavelengths).
std::vector<double> default_wavelengths();

// How orders >= 2 collect sunlight (see METHOD above).
enum class MsEstimator { kCollision, kLitSegment };

struct ReferenceSettings {
    int scattering_orders = 4;          // 1 = single scattering + direct ground reflection only
    double panel_height_m = 250.0;      // altitude per quadrature panel for order 1 and transmittance
    double ms_panel_height_m = 1500.0;  // the same for the Monte Carlo paths (cost vs exactness)
    int ms_paths = 4096;                // Monte Carlo paths per sky() query (the first batch if adaptive)
    int ms_max_paths = 0;               // adaptive: double up to this many paths (<= ms_paths: fixed count)
    double ms_target_noise = 0.0;       // adaptive: stop at stderr <= this fraction of the luminance
    double ms_target_floor = 0.0;       // adaptive: ... or of this luminance (cd m^-2) where it is larger
    MsEstimator ms_estimator = MsEstimator::kLitSegment;
    std::uint64_t seed = 1;
    int ms_first_order = 2;  // 1: the Monte Carlo also estimates order 1 (validation)
    std::vector<double> wavelengths_nm = default_wavelengths();  // increasing, >= 2
};

struct SkyQuery {
    double altitude_m = 0.0;       // camera above the ground (clamped to kMinCameraAltitude)
    double view_zenith_deg = 0.0;  // 0 = zenith, 90 = horizon, > 90 below it
    double sun_zenith_deg = 0.0;
    double relative_azimuth_deg = 0.0;  // azimuth of the Sun minus that of the view direction
};

struct SkyRadiance {
    glm::dvec3 rgb{0.0};  // linear sRGB, photometric scale (cd m^-2 in luminance)
    glm::dvec3 xyz{0.0};
    double luminance = 0.0;        // cd m^-2
    std::vector<double> spectrum;  // W m^-2 sr^-1 nm^-1 at ReferenceSettings::wavelengths_nm

    // Components. spectrum = single + ground + multiple (with ms_first_order = 1 it is the
    // Monte Carlo estimate alone, orders 1..N, while single and ground still hold the
    // deterministic order 1 for comparison).
    std::vector<double> single_spectrum;    // order-1 in-scattering along the view ray
    std::vector<double> ground_spectrum;    // direct sunlight reflected by the ground (order 1)
    std::vector<double> multiple_spectrum;  // Monte Carlo, orders ms_first_order..N
    std::vector<double> multiple_stderr;    // standard error of multiple_spectrum, per wavelength
    double single_luminance = 0.0, ground_luminance = 0.0;
    double multiple_luminance = 0.0, multiple_luminance_stderr = 0.0;
    glm::dvec3 multiple_rgb{0.0}, multiple_rgb_stderr{0.0};
    int ms_paths = 0;  // paths actually traced (more than ReferenceSettings::ms_paths if adaptive)

    bool hits_ground = false;   // the view ray ends on the ground
    bool in_atmosphere = true;  // false: a camera in space whose ray misses the atmosphere
};

class ReferenceIntegrator {
public:
    ReferenceIntegrator(AtmosphereParameters params, ReferenceSettings settings = {});

    const AtmosphereParameters& parameters() const { return params_; }
    const ReferenceSettings& settings() const { return settings_; }
    const std::vector<double>& wavelengths() const { return settings_.wavelengths_nm; }
    const SpectralToColor& color() const { return color_; }

    // Density-weighted path lengths (m) of (Rayleigh, Mie, ozone) along the ray from radius r with
    // zenith cosine mu over [0, length] (inside the shell; density is 0 above top_radius).
    glm::dvec3 column_density(double r, double mu, double length) const;
    // Per-wavelength optical depth over the same path.
    std::vector<double> optical_depth(double r, double mu, double length) const;
    // Per-wavelength transmittance from (r, mu) to the nearest boundary (ground or top).
    std::vector<double> transmittance(double r, double mu) const;

    SkyRadiance sky(const SkyQuery& query) const;

    // Per-wavelength coefficients at density 1 (m^-1), for tests and for later models.
    const std::vector<double>& rayleigh_scattering() const { return beta_r_; }
    const std::vector<double>& mie_scattering() const { return beta_ms_; }
    const std::vector<double>& mie_extinction() const { return beta_me_; }
    const std::vector<double>& ozone_absorption() const { return beta_o_; }
    const std::vector<double>& solar_irradiance() const { return sun_; }

    struct Segment;  // a ray with its quadrature panels (defined in the .cpp)

private:
    glm::dvec3 densities(const glm::dvec3& p) const;
    Segment make_segment(const glm::dvec3& origin, const glm::dvec3& dir, double length, double panel_h,
                         const std::vector<double>& extra_splits) const;
    glm::dvec3 segment_column(const Segment& s, double t) const;
    double sample_segment(const Segment& s, const glm::dvec3& sigma, double tau_target) const;
    // Spectral transmittance toward the Sun from p (0 when the ground blocks it) into out.
    void sun_transmittance(const glm::dvec3& p, const glm::dvec3& sun, double panel_h, std::vector<double>& out) const;
    void single_scattering(const glm::dvec3& o, const glm::dvec3& v, double length, bool hits_ground,
                           const glm::dvec3& sun, SkyRadiance& out) const;
    void multiple_scattering(const glm::dvec3& o, const glm::dvec3& v, double length, bool hits_ground,
                             const glm::dvec3& sun, SkyRadiance& out) const;
    // The steps of multiple_scattering(): one path from the camera, and at each order either a
    // bounce off the ground or a collision in the air (false: the path ends there).
    struct MsPath;
    void trace_ms_path(MsPath& path, double length, bool hits_ground, const glm::dvec3& sun) const;
    bool ms_surface_bounce(MsPath& path, int order, double len, double alpha, const glm::dvec3& sun) const;
    bool ms_volume_scatter(MsPath& path, int order, const Segment& s, double t, double alpha,
                           const glm::dvec3& sun) const;
    // MsEstimator::kLitSegment: the line sample of the sunlight scattered along segment s.
    void ms_lit_segment_nee(MsPath& path, const Segment& s, const glm::dvec3& sun) const;
    void ms_add_sunlight(MsPath& path, const Segment& s, double t, double weight, const glm::dvec3& sun) const;
    // The sampling density's stand-in for the transmittance toward the Sun: luminance-weighted,
    // tabulated over (r, mu_s) (0 where the ground blocks the Sun).
    void build_sun_proxy();
    // kLitSegment, x in the planet's shadow: the axis of the twilight direction lobe (false: none).
    bool ms_twilight_axis(const glm::dvec3& x, const glm::dvec3& sun, glm::dvec3& axis) const;
    double sun_proxy(const glm::dvec3& p, const glm::dvec3& sun) const;

    AtmosphereParameters params_;
    ReferenceSettings settings_;
    SpectralToColor color_;
    std::vector<double> beta_r_, beta_ms_, beta_me_, beta_o_, sun_, albedo_;
    std::vector<double> sun_proxy_log_;  // log of the proxy, kProxyR x kProxyMu
    std::size_t proxy_k_ = 0;            // wavelength of the proxy's view transmittance (nearest 550 nm)
};

}  // namespace cupola::atmosphere

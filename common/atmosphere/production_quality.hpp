#pragma once
// Quality levels of the production atmosphere: table sizes, integration counts, per-pixel march
// samples, and whether the analytic fast mode (Ekelin & Fernqvist 2009) replaces the tables. Chosen by name in
// scene files and on the command line (`--model`); docs/atmosphere-speed-vs-error.md measures each.
#include <string>
#include <vector>

namespace cupola::atmosphere {

struct ProductionQuality {
    std::string name;
    bool analytic = false;  // the analytic fast mode: no tables beyond the fit, no march
    bool multiple_scattering = true;
    int transmittance_width = 256, transmittance_height = 64, transmittance_steps = 40;
    int ms_size = 32, ms_directions = 64, ms_steps = 20;
    int ms_order_directions = 0;  // directions of the orders >= 3 (atm_compute_ms_next_order); 0: ms_directions
    int ms_orders = 6;            // highest order iterated explicitly; 0: Hillaire's J_2 / (1 - f_ms) instead
    // The Rayleigh part of the multiple scattering weighted by the anisotropy of the light arriving
    // from the first scattering (atm_ms_rayleigh_factor), instead of isotropic.
    bool ms_rayleigh_anisotropy = false;
    int irradiance_width = 64, irradiance_height = 16, irradiance_directions = 64, irradiance_samples = 16;
    int view_samples = 16;  // per-pixel march steps
    // The sky as look-ups (atmosphere_sky_view.glsl): a sky-view table per frame instead of the
    // per-pixel march; its size (W x H, H even) and march steps per texel.
    bool sky_view = false;
    int sky_view_width = 96, sky_view_height = 128, sky_view_samples = 32;
    // Sample wavelengths of the table's march: 3 (680/550/440 nm, as the march levels) or 6 (a
    // second triplet 610/500/400 nm with its own tables, atmosphere_color.glsl).
    int sky_view_wavelengths = 3;

    // The table-defining fields (not view_samples): what the disk cache key covers.
    std::string table_key() const;
};

// The named levels: "analytic", "single" (tables, no multiple scattering), "hillaire" (medium
// with Hillaire's geometric multiple-scattering tail), "low", "medium" (the per-pixel march: the
// GPU-side reference), "sky-view-rgb" and "sky-view" (the default: medium's tables looked up
// through a per-frame sky-view table, from three or six sample wavelengths). Throws
// std::invalid_argument listing the valid names.
ProductionQuality production_quality(const std::string& name);
std::vector<std::string> production_quality_names();
inline constexpr const char* kDefaultProductionQuality = "sky-view";

}  // namespace cupola::atmosphere

#pragma once
// The production atmosphere model on the CPU: the same shared shading code the GPU pass runs
// (shaders/shared/atmosphere_*.glsl, three sample wavelengths in float), with its tables and
// colour matrix. Used by the cupola-atmosphere probe, the accuracy tests, the master's
// cluster-wide exposure, and to fill the GPU pass's uniforms.
//
// Colour: the model computes radiance per unit solar irradiance at 680/550/440 nm; the spectrum
// is rebuilt from those samples and integrated against the solar spectrum and the CIE functions
// (atm_samples_to_xyz, production_color.hpp): photometric linear sRGB, luminance in cd m^-2 --
// the same units as the reference integrator.
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "atmosphere/atmosphere_parameters.hpp"
#include "atmosphere/production_color.hpp"
#include "atmosphere/production_quality.hpp"
#include "atmosphere/production_tables.hpp"
#include "atmosphere/reference_integrator.hpp"
#include "atmosphere/sky_view_table.hpp"
#include "shading/shared_shading.hpp"

namespace cupola::atmosphere {

// The sample wavelengths of the three channels (defined once, in atmosphere_color.glsl).
inline const double kProductionWavelengths[3] = {shading::ATM_LAMBDA_R, shading::ATM_LAMBDA_G, shading::ATM_LAMBDA_B};
// The sky-view level's second triplet (atmosphere_color.glsl).
inline const double kProductionWavelengths2[3] = {shading::ATM_LAMBDA2_R, shading::ATM_LAMBDA2_G,
                                                  shading::ATM_LAMBDA2_B};

// Linear sRGB -> CIE XYZ: the exact inverse of xyz_to_linear_srgb (star_color.glsl).
glm::dvec3 linear_srgb_to_xyz(const glm::dvec3& rgb);

// The uniform struct of the shared code, at the three sample wavelengths.
shading::AtmosphereParams to_shader_params(const AtmosphereParameters& p);
// The same at the wavelengths `lambdas_nm` (channels x, y, z), each one a node of the spectral
// reconstruction's grid `grid_nm` (increasing), over which the ozone is band-averaged.
shading::AtmosphereParams to_shader_params(const AtmosphereParameters& p, const glm::dvec3& lambdas_nm,
                                           const std::vector<double>& grid_nm);
// The six sample wavelengths of the sky-view level, increasing.
std::vector<double> sky_view_wavelength_grid();

// Fit of the analytic mode's sunlight function E_sun (Ekelin & Fernqvist 2009, section 3.2.1) to
// the model's own transmittance toward the Sun at half a Rayleigh scale height (least squares over
// sun zenith 0..110 degrees).
shading::AtmosphereAnalyticFit fit_analytic_sun(const shading::AtmosphereParams& a);

struct ProductionRadiance {
    glm::dvec3 rgb{0.0};  // linear sRGB, cd m^-2 scale
    glm::dvec3 xyz{0.0};
    double luminance = 0.0;         // cd m^-2
    glm::dvec3 transmittance{1.0};  // along the view ray, at the sample wavelengths
    bool hits_ground = false;
    bool in_atmosphere = true;
};

class ProductionAtmosphere {
public:
    ProductionAtmosphere(AtmosphereParameters params, ProductionQuality quality, const TableCacheOptions& cache = {});

    const AtmosphereParameters& parameters() const { return params_; }
    const ProductionQuality& quality() const { return quality_; }
    const shading::AtmosphereParams& shader_params() const { return gpu_; }
    const shading::AtmosphereAnalyticFit& analytic_fit() const { return fit_; }
    const ProductionTables& tables() const { return tables_; }
    // The second triplet (kProductionWavelengths2) of a six-wavelength sky-view level, with its
    // tables; otherwise unset (empty tables).
    bool six_wavelengths() const { return quality_.sky_view && quality_.sky_view_wavelengths == 6; }
    const shading::AtmosphereParams& shader_params2() const { return gpu2_; }
    const ProductionTables& tables2() const { return tables2_; }
    const shading::Texture2DData& color_weights() const { return color_weights_; }
    // Per unit solar irradiance at the sample wavelengths -> CIE XYZ (Y in cd m^-2).
    glm::dvec3 to_xyz(const glm::vec3& f) const;

    // The same query as ReferenceIntegrator::sky (the ground's albedo from the parameters). With
    // a sky-view quality the answer is looked up in the table for the query's camera and Sun, as
    // the GPU looks its pixels up.
    ProductionRadiance sky(const SkyQuery& query) const;
    // The sky-view table for a camera distance and Sun zenith cosine (built once, then kept).
    const SkyViewTable& sky_view_table(float d_m, float mu_s) const;

    // Per unit solar irradiance at the sample wavelengths, for a ray in the shared code's terms;
    // t_geometry < 0: no scene geometry. Adds the lit ground when the ray ends on it.
    glm::vec3 radiance(const shading::AtmosphereRayStart& start, float t_geometry, glm::vec3* transmittance) const;
    // The same under eclipse shadows: `shadow` as atm_view_ray_shadowed takes it (its casters in
    // exact or fast mode; the lookup table is not available here and counts as exact).
    glm::vec3 radiance(const shading::AtmosphereRayStart& start, float t_geometry, glm::vec3* transmittance,
                       shading::EclipseRay shadow) const;
    // The same light in two parts, unshadowed and without scene geometry: the air's in-scatter, and
    // what the ground adds per unit ground albedo, seen through the air (zero where the ray misses
    // it). radiance() = air + ground_albedo * ground_per_albedo.
    struct RadianceParts {
        glm::vec3 air{0.0f}, ground_per_albedo{0.0f};
    };
    RadianceParts radiance_parts(const shading::AtmosphereRayStart& start) const;

private:
    RadianceParts radiance_parts(const shading::AtmosphereRayStart& st, float t_geometry, glm::vec3* transmittance,
                                 shading::EclipseRay shadow) const;
    ProductionRadiance sky_from_table(const shading::AtmosphereRayStart& st, float d_m, const glm::vec3& v,
                                      const glm::vec3& sun) const;

    AtmosphereParameters params_;
    ProductionQuality quality_;
    shading::AtmosphereParams gpu_{}, gpu2_{};
    shading::AtmosphereAnalyticFit fit_{};
    ProductionTables tables_, tables2_;
    shading::Texture2DData color_weights_;
    struct SkyViewCache {  // tables by (d_m, mu_s); shared by copies of the model (same parameters)
        std::mutex mutex;
        std::map<std::pair<float, float>, std::unique_ptr<SkyViewTable>> tables;
    };
    std::shared_ptr<SkyViewCache> sky_view_cache_ = std::make_shared<SkyViewCache>();
};

}  // namespace cupola::atmosphere

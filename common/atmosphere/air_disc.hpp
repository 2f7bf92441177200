#pragma once
// A planet with air as a distant observer sees it whole: the light of its disc, the air's
// in-scatter and the ground seen through the air, summed over the top-of-atmosphere disc on the CPU
// by the production model the slaves draw from (ProductionAtmosphere::radiance_parts). For a
// distant observer it depends only on the phase angle (Sun - planet - observer) and falls as the
// square of the distance, so it is tabulated once per model (every 5 degrees of phase) and scaled.
// A planet with air smaller than a few pixels is drawn as a point carrying this light
// (passes/planet_light, with_air), so that its point and the air's disc carry the same energy at
// the handover from one to the other.
#include <vector>

#include "atmosphere/production_model.hpp"

namespace cupola::atmosphere {

class AirDiscCurve {
public:
    static constexpr double kPhaseStepDeg = 5.0;
    explicit AirDiscCurve(const ProductionAtmosphere& model);

    // The disc's radiance times its solid angle in linear sRGB (cd m^-2 sr in luminance, per unit
    // of the model's physical solar irradiance: times solar_scale for scene units) seen from
    // distance_m (centre to observer, far outside the air) at phase_deg, over a uniform ground of
    // linear reflectance ground_rgb (albedo; the air's part is independent of it).
    glm::dvec3 flux_rgb(double phase_deg, const glm::dvec3& ground_rgb, double distance_m) const;
    // The two parts, times the distance squared (cd m^-2 m^2, linear sRGB), at a tabulated phase step.
    const glm::dvec3& air_at(int step) const { return air_[static_cast<size_t>(step)]; }
    const glm::dvec3& ground_at(int step) const { return ground_[static_cast<size_t>(step)]; }

private:
    std::vector<glm::dvec3> air_, ground_;
};

}  // namespace cupola::atmosphere

#pragma once
// Error of a production atmosphere model against the stored reference dataset, per validation
// group (camera x sun zenith) and overall. Luminance error is relative, in linear radiance:
// |Y_production - Y_reference| / max(Y_reference, kLuminanceFloor) -- the floor keeps rays in the
// planet's shadow (reference ~1e-12 cd m^-2, nothing a display or an eye can show) from
// dominating the statistics; they are counted in `below_floor`; the chromaticity error is the CIE
// 1976 u'v' distance (0.004 is about one just-noticeable difference). Rays that miss the
// atmosphere are counted as skipped, and must be exactly 0 in the model too (counted in
// nonzero_where_reference_is_zero).
#include <string>
#include <vector>

#include "atmosphere/production_model.hpp"
#include "atmosphere/reference_dataset.hpp"

namespace cupola::atmosphere {

// 1e-4 cd m^-2: below the natural night sky (airglow and starlight, ~2e-4 cd m^-2).
inline constexpr double kLuminanceFloor = 1e-4;
// Rows whose reference is itself uncertain by more than this (Monte Carlo standard error over
// luminance) cannot measure a model to the 2 % target; they are left out of the statistics and
// counted in `reference_limited` (docs/atmosphere-speed-vs-error.md reports them). Since the
// reference's line-sampled, adaptive estimator (common/atmosphere/reference_integrator.hpp) such
// rows are few: the night side seen from space, lit only by light scattered more than once from
// the distant twilight ring (data/atmosphere/PROVENANCE.md gives the counts per group).
inline constexpr double kMaxReferenceNoise = 0.05;

// True when the stored reference row cannot judge a model: exactly 0 (no Monte Carlo path reached
// sunlight, 0 +- unknown) or noisier than kMaxReferenceNoise.
bool reference_is_limited(const ReferenceRow& row);

struct ErrorStats {
    std::string camera;          // "all" for the overall entry
    double sun_zenith_deg = -1;  // -1 for "all suns"
    int used = 0, skipped = 0, nonzero_where_reference_is_zero = 0, below_floor = 0, reference_limited = 0;
    double median = 0, p99 = 0, max = 0;  // relative luminance error
    double mean_signed = 0;               // mean of (Y_p - Y_r) / Y_r: the bias
    double chroma_median = 0, chroma_p99 = 0;
    double reference_noise_median = 0;  // median of the reference's relative standard error
};

struct AccuracyReport {
    std::vector<ErrorStats> groups;
    ErrorStats overall;
    double seconds_per_query = 0;  // CPU time of the production model per query (not the GPU cost)
};

AccuracyReport measure_accuracy(const ProductionAtmosphere& model, const ReferenceDataset& reference);

// CIE 1976 u'v' of an XYZ colour ((0, 0) for black).
glm::dvec2 chromaticity_uv(const glm::dvec3& xyz);

}  // namespace cupola::atmosphere

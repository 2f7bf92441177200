#pragma once
// The eye's adaptation and the exposure the master decides from it, once per frame for the whole
// cluster (the values travel in the snapshot: RenderSettings::exposure, tone_white, adapted_cd_m2).
//
//  - Adaptation: the adapted luminance approaches the metered log-average (exposure/sky_metering)
//    exponentially in log luminance, with one time constant toward brighter (light adaptation,
//    about a second) and a much longer one toward darker (dark adaptation, minutes), the
//    asymmetric time course of the time-dependent adaptation models (Pattanaik, Tumblin, Yee and
//    Greenberg 2000, §4). The first frame starts adapted.
//  - The key: the display value given to the adapted luminance. It is the configured key (0.18,
//    mid grey) in daylight, and falls at night after Krawczyk, Myszkowski and Seidel (2005, §4.1):
//    key = 1.03 - 2 / (2 + log10(L + 1)), so that a night sky is shown dark, not lifted to grey.
//  - The exposure: key / adapted luminance, clamped to the configured range.
//  - The display white: the exposed highlight of the metering (never below 1: at a white of 1
//    the tone curve is the identity up to 1), so the highlights roll off rather than clip.
#include <optional>

#include "config/cluster_config.hpp"
#include "exposure/sky_metering.hpp"

namespace cupola {

// The darkest adaptation the eye is given (cd/m^2): a sky with nothing lit adapts to this.
constexpr double kDarkestAdaptation_cd_m2 = 1e-6;

struct ExposureDecision {
    double exposure = 1.0;
    double tone_white = 0.0;  // exposed luminance shown as white (0: no curve)
    double adapted_cd_m2 = 0.0;
};

// Krawczyk, Myszkowski and Seidel (2005, §4.1)'s key for a log-average luminance L (cd/m^2).
double adaptation_key(double adapted_cd_m2);

// The adapted luminance after dt_s with the metered target, from `adapted` (both > 0).
double adapt_luminance(double adapted_cd_m2, double target_cd_m2, double dt_s, const AutoExposureConfig& c);

// The target of adaptation for a metering: its log-average, at least the darkest adaptation.
double adaptation_target(const SkyMetering& m);

ExposureDecision decide_exposure(const SkyMetering& m, double adapted_cd_m2, const AutoExposureConfig& c);

// The master's adaptation state across frames.
class EyeAdaptation {
public:
    // The adapted luminance for a frame dt_s after the previous one; the first frame adapts at once.
    double step(double target_cd_m2, double dt_s, const AutoExposureConfig& c);
    std::optional<double> adapted() const { return adapted_; }

private:
    std::optional<double> adapted_;
};

}  // namespace cupola

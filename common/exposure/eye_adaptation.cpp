#include "exposure/eye_adaptation.hpp"

#include <algorithm>
#include <cmath>

namespace cupola {

double adaptation_key(double adapted_cd_m2) {
    return 1.03 - 2.0 / (2.0 + std::log10(std::max(adapted_cd_m2, 0.0) + 1.0));
}

double adapt_luminance(double adapted_cd_m2, double target_cd_m2, double dt_s, const AutoExposureConfig& c) {
    const double tau_s = target_cd_m2 > adapted_cd_m2 ? c.light_adaptation_s : c.dark_adaptation_s;
    const double reach = tau_s > 0.0 ? 1.0 - std::exp(-std::max(dt_s, 0.0) / tau_s) : 1.0;
    return std::exp(std::log(adapted_cd_m2) + (std::log(target_cd_m2) - std::log(adapted_cd_m2)) * reach);
}

double adaptation_target(const SkyMetering& m) { return std::max(m.log_average, kDarkestAdaptation_cd_m2); }

ExposureDecision decide_exposure(const SkyMetering& m, double adapted_cd_m2, const AutoExposureConfig& c) {
    ExposureDecision d;
    d.adapted_cd_m2 = adapted_cd_m2;
    const double key = c.key_follows_adaptation ? std::min(c.key, adaptation_key(adapted_cd_m2)) : c.key;
    d.exposure = std::clamp(key / adapted_cd_m2, c.min_exposure, c.max_exposure);
    if (m.highlight > 0.0) d.tone_white = std::max(1.0, d.exposure * m.highlight);
    return d;
}

double EyeAdaptation::step(double target_cd_m2, double dt_s, const AutoExposureConfig& c) {
    adapted_ = adapted_ ? adapt_luminance(*adapted_, target_cd_m2, dt_s, c) : target_cd_m2;
    return *adapted_;
}

}  // namespace cupola

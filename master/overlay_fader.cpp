#include "overlay_fader.hpp"

#include <algorithm>

namespace cupola {

std::array<bool, kOverlayCount> overlay_targets(const ShowSettings& settings, const SceneConfig& scene) {
    std::array<bool, kOverlayCount> out{};
    for (size_t k = 0; k < kOverlayCount; ++k)
        out[k] = scene.overlays.present && settings.overlays[k].value_or(scene.overlays.styles[k].visible);
    return out;
}

OverlayFader::OverlayFader(const SceneConfig& scene) {
    for (size_t k = 0; k < kOverlayCount; ++k) fade_s_[k] = scene.overlays.styles[k].fade_s;
}

std::array<float, kOverlayCount> OverlayFader::step(const std::array<bool, kOverlayCount>& targets, double dt_s) {
    for (size_t k = 0; k < kOverlayCount; ++k) {
        const float target = targets[k] ? 1.0f : 0.0f;
        if (!started_ || !(fade_s_[k] > 0.0)) {
            alpha_[k] = target;
            continue;
        }
        const float reach = static_cast<float>(std::max(dt_s, 0.0) / fade_s_[k]);
        alpha_[k] = target > alpha_[k] ? std::min(target, alpha_[k] + reach) : std::max(target, alpha_[k] - reach);
    }
    started_ = true;
    return alpha_;
}

}  // namespace cupola

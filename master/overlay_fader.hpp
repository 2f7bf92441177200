#pragma once
// The overlays' opacities, decided by the master once per frame for the whole cluster
// (RenderSettings::overlay_alpha): each moves toward 1 when its overlay is shown and toward 0 when
// hidden, linearly over the overlay's fade_s (scene config), so every channel fades alike.
#include <array>

#include "config/scene_config.hpp"
#include "show_script.hpp"

namespace cupola {

// Whether each overlay is shown: the show's or the presenter's switch, else the scene's `visible`.
std::array<bool, kOverlayCount> overlay_targets(const ShowSettings& settings, const SceneConfig& scene);

class OverlayFader {
public:
    explicit OverlayFader(const SceneConfig& scene);
    // The opacities after dt_s toward the targets (the first call starts at the targets).
    std::array<float, kOverlayCount> step(const std::array<bool, kOverlayCount>& targets, double dt_s);

private:
    std::array<double, kOverlayCount> fade_s_{};
    std::array<float, kOverlayCount> alpha_{};
    bool started_ = false;
};

}  // namespace cupola

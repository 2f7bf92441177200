#pragma once
// The text of the text overlays and where each piece stands on the sky: the constellations' names
// at their figures' label points, the cardinal points on the horizon, and the names of the bodies
// and of the brightest named stars (V <= 1.6, proper names only). A label is anchored at a
// direction in its overlay's frame (overlay_frames.hpp); bodies' labels are anchored each frame at
// the body's direction from the camera (anchor unused).
#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

#include "config/scene_config.hpp"
#include "overlay/constellation_figures.hpp"
#include "overlay/overlay_kind.hpp"
#include "scene/star_catalog.hpp"

namespace cupola {

enum class LabelPlacement {
    Centred,  // centred on the anchor (names of constellations, cardinal points)
    Beside,   // to the right of the anchor, clear of the object's own light (stars, bodies)
};

struct OverlayLabel {
    OverlayKind kind = OverlayKind::Labels;
    std::string text;
    glm::dvec3 anchor{0.0, 0.0, 1.0};
    LabelPlacement placement = LabelPlacement::Centred;
    std::optional<uint16_t> body;  // a scene body: anchored at it every frame
};

// stars: the scene's catalogue (those of V <= 1.6 with a proper name are labelled).
std::vector<OverlayLabel> overlay_labels(const std::vector<ConstellationFigure>& figures, const SceneConfig& scene,
                                         const std::vector<Star>& stars);

}  // namespace cupola

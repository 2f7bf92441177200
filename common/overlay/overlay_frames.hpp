#pragma once
// The frames the overlays are drawn in, for one snapshot: every channel derives them from the same
// snapshot by the same rule, so the overlays lie alike on every channel.
//   equatorial  the world frame itself (ICRS/J2000 axes): z the celestial north pole, x the
//               vernal equinox
//   ecliptic    z the ecliptic north pole, x the equinox: the equatorial frame turned about x by
//               the mean obliquity at J2000, 84381.406 arcseconds (IAU 2006; Capitaine et al. 2003)
//   horizon     the observer's ground: z the zenith, x north, y west (right-handed), from the
//               body the camera stands on (the nearest planet or moon within one radius of its
//               surface) and its spin axis; absent elsewhere, and the overlays drawn in it with it
#include <glm/glm.hpp>

#include <optional>

#include "config/scene_config.hpp"
#include "overlay/overlay_kind.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

enum class OverlayFrame { Equatorial, Ecliptic, Horizon };

// The frame each overlay is drawn in (the labels of bodies: the world's, that is Equatorial).
OverlayFrame overlay_frame_of(OverlayKind kind);

struct OverlayFrames {
    glm::dmat3 ecliptic{1.0};                  // ecliptic -> world
    std::optional<glm::dmat3> horizon;         // (north, west, zenith) -> world, when on a body
    std::optional<uint16_t> ground_body;       // the body whose ground that is
    glm::dvec3 label_up_world{0.0, 0.0, 1.0};  // text stands up toward this: the zenith, else the pole

    // frame -> world; nullopt for the horizon frame when there is none.
    std::optional<glm::dmat3> to_world(OverlayFrame f) const;
};

OverlayFrames overlay_frames(const Snapshot& snap, const SceneConfig& scene);

}  // namespace cupola

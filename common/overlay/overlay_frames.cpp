#include "overlay/overlay_frames.hpp"

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <limits>

namespace cupola {

namespace {

constexpr double kObliquityJ2000_rad = 84381.406 / 3600.0 * glm::pi<double>() / 180.0;

// The nearest planet or moon whose surface is within one radius of the camera.
const BodyState* ground_under(const Snapshot& snap, const SceneConfig& scene) {
    const BodyState* best = nullptr;
    double best_gap = std::numeric_limits<double>::infinity();
    for (const BodyState& b : snap.bodies) {
        if (b.id >= scene.bodies.size()) continue;
        const BodyConfig& c = scene.bodies[b.id];
        if (c.kind == BodyKind::Star) continue;
        const double gap = glm::length(snap.camera_position_m - b.position_m) - c.radius_m;
        if (gap < c.radius_m && gap < best_gap) {
            best_gap = gap;
            best = &b;
        }
    }
    return best;
}

}  // namespace

OverlayFrame overlay_frame_of(OverlayKind kind) {
    switch (kind) {
        case OverlayKind::GridAltAz:
        case OverlayKind::Horizon:
        case OverlayKind::Meridian:
        case OverlayKind::Cardinals:
            return OverlayFrame::Horizon;
        case OverlayKind::GridEcliptic:
            return OverlayFrame::Ecliptic;
        default:
            return OverlayFrame::Equatorial;
    }
}

std::optional<glm::dmat3> OverlayFrames::to_world(OverlayFrame f) const {
    switch (f) {
        case OverlayFrame::Equatorial:
            return glm::dmat3(1.0);
        case OverlayFrame::Ecliptic:
            return ecliptic;
        case OverlayFrame::Horizon:
            return horizon;
    }
    return std::nullopt;
}

OverlayFrames overlay_frames(const Snapshot& snap, const SceneConfig& scene) {
    OverlayFrames f;
    const double c = std::cos(kObliquityJ2000_rad), s = std::sin(kObliquityJ2000_rad);
    f.ecliptic = glm::dmat3(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, c, s), glm::dvec3(0.0, -s, c));
    const BodyState* ground = ground_under(snap, scene);
    if (!ground) return f;
    const glm::dvec3 zenith = glm::normalize(snap.camera_position_m - ground->position_m);
    const glm::dmat3 body_to_world = glm::mat3_cast(ground->orientation);
    glm::dvec3 north = body_to_world[2] - glm::dot(body_to_world[2], zenith) * zenith;  // toward the spin axis
    if (glm::length(north) < 1e-9)  // at a pole: any direction is south (or north); take the body's x
        north = body_to_world[0] - glm::dot(body_to_world[0], zenith) * zenith;
    north = glm::normalize(north);
    f.horizon = glm::dmat3(north, glm::cross(zenith, north), zenith);
    f.ground_body = ground->id;
    f.label_up_world = zenith;
    return f;
}

}  // namespace cupola

#pragma once
// Analytic visibility of a glare source disc (the Sun) behind spherical occluders, on the CPU in
// double: the glare fallback's visible fraction and the offset of the visible part's centroid.
//
// FRACTION. The same math as the eclipse shadows (shaders/shared/eclipse_shadow.glsl through
// common/shading/shared_shading.hpp): per occluder eclipse_discs (camera-relative vectors formed
// in double, then rounded to float) and eclipse_visible_exact(a, s, u = 0), i.e. the visible
// AREA fraction of a uniform disc; several occluders multiply, as eclipse_light does for several
// casters. One regime bypasses eclipse_discs: a HUGE occluder (the ground under a camera standing
// on a planet, angular radius >= kStraightEdgeAngle, or so close to 90 degrees that the source
// disc can reach past it). There eclipse_discs fails twice: its "behind the point" test
// (dot(to_sun, to_caster) <= 0) drops the planet while the Sun's centre sits between the
// astronomical horizon and the geometric one (the horizon dip, 0.045 deg for a camera 2 m up),
// so a Sun half set reads fully visible; and its float asin of r / d ~ 1 - 3e-7 puts the limb
// ~0.005 Sun radii off. That regime uses the straight-edge limit in double instead: the limb
// is locally a straight line across the source disc at signed angular distance
// h = theta - rho from the disc's centre (theta: angle source centre - occluder centre, rho: the
// occluder's angular radius, both exact on the sphere), and the visible fraction is that of a
// disc cut by a chord, 1 - (alpha - sin alpha cos alpha) / pi with cos alpha = h / sigma. It is
// the a -> infinity limit of eclipse_visible_exact (tests/test_glare_visibility.cpp checks the
// two agree at a = 20000, where eclipse_visible_exact itself is still fine but float s = a + h
// only resolves h to 0.002). The threshold is where the two models' edge curvatures err equally
// against the true one (the limb's geodesic curvature cot rho, versus 1 / rho for the flat
// lens and 0 for the straight edge: tan rho = 2 rho); either side, for the Sun, the error of the
// visible fraction stays below ~2.5e-4 (measured against ray casting at the threshold, where it
// is largest).
//
// CENTROID. The visible part is the disc minus the lens(es); with the disc's own centroid at the
// centre, centroid = -sum_k A_k c_k / A_visible, A_visible = pi sigma^2 - sum_k A_k. Each lens
// (area A_k, centroid c_k on the line of centres) is the sum of two circular segments (radius R,
// half-angle alpha: area R^2 (alpha - sin alpha cos alpha), centroid 2 R sin^3 alpha /
// (3 (alpha - sin alpha cos alpha)) from that circle's centre), worked out in double in the
// tangent plane at the source with angles (apparent radii asin(R / d); small-angle, fine for
// the Sun's 0.27 deg) and returned as a world-frame vector in radians. In the straight-edge
// regime the lens is the source's segment beyond the chord.
//
// LIMITATIONS. Several occluders: the fraction is the eclipse code's product, which differs from
// the true area fraction by the cross terms: (1 - x1)(1 - x2) against 1 - x1 - x2 for disjoint
// lenses hiding x1 and x2 of the disc (0.0025 for holes of 0.2 and 0.25 Sun radii); the centroid
// assumes the lenses do not overlap each other (overlapping ones are double-counted; should
// their areas sum past the disc's, the offset is zero). One occluder, the glare case that matters
// (Moon or horizon), has neither error. The flat (tangent-plane) model assumes a small source
// disc: its angular radius should stay well below pi / 2 - kStraightEdgeAngle (~23 deg). An
// occluder straddling the source's distance counts entirely or not at all, by its near side (see
// analytic_visibility). The camera must be outside the source (else: unoccluded); a zero-radius
// source is a point, visible or not.
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "config/scene_config.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

struct SphereOccluder {
    glm::dvec3 center_m;
    double radius_m;
};

struct GlareVisibility {
    double visible_fraction = 1.0;    // of the source disc's area, [0, 1]
    glm::dvec3 centroid_offset{0.0};  // world frame, radians: from the disc centre toward the
                                      // centroid of its visible part, perpendicular to the
                                      // source direction (zero when unoccluded or fully hidden)
};

// Occluders whose angular radius reaches this (radians) are treated with the straight-edge limit
// (see above): tan(rho) = 2 rho, ~66.8 deg.
inline constexpr double kStraightEdgeAngle = 1.1655611852072114;

// The source disc (centre, radius) seen from the camera behind spherical occluders. An occluder
// only counts when it is in front of the source (its near side closer than the source centre)
// and in front of the camera; a camera inside an occluder sees nothing (fraction 0).
GlareVisibility analytic_visibility(const glm::dvec3& camera_m, const glm::dvec3& source_center_m,
                                    double source_radius_m, const std::vector<SphereOccluder>& occluders);

// Convenience: every non-star body of the snapshot except the source itself as an occluder;
// airless_only: only the bodies without an atmosphere.
std::vector<SphereOccluder> snapshot_occluders(const Snapshot& snap, const SceneConfig& scene, uint16_t source_body_id,
                                               bool airless_only = false);

}  // namespace cupola

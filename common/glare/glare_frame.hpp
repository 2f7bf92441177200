#pragma once
// The cluster-wide frame around a glare source, and what the master and the slaves must compute
// identically from it: the glare's axes (so every channel draws the same streaks), the wedges
// the occlusion queries are split into, and the direction toward the visible part of a partly
// hidden source built from the wedges' sums.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "projection/channel_frustum.hpp"
#include "wire/reports.hpp"

namespace cupola {

struct GlareFrame {
    glm::dvec3 center{0.0, 0.0, -1.0};  // unit, toward the source (world frame)
    glm::dvec3 right{1.0, 0.0, 0.0};    // unit, perpendicular to center
    glm::dvec3 up{0.0, 1.0, 0.0};       // unit: toward the dome apex as seen around the source
};

// Axes from the shared camera orientation only (the camera's up is the dome apex), never from a
// channel: right = center x up_camera, up = right x center. Near the apex (center within 1e-6
// of up) the camera's -Z takes the place of up.
GlareFrame glare_frame(const glm::dvec3& center_world, const glm::dquat& camera_orientation);

// Wedge i of GlareMeasurement::kWedges covers the angles [i, i + 1) * 2 pi / kWedges measured
// from `right` toward `up`.
double glare_wedge_mid_angle(int wedge);

// Offset (world, radians) from the source's centre toward the centroid of its visible part,
// estimated from the visible solid angle per wedge: each wedge's share sits at the centroid
// radius of a full wedge of a disc of the source's angular radius, 2/3 R sin(h)/h (h = half the
// wedge angle). Exact for a disc cut by a chord through its centre; zero when nothing is visible.
glm::dvec3 glare_centroid_offset(const GlareFrame& frame, const float (&visible_sr)[GlareMeasurement::kWedges],
                                 double angular_radius);

// Whether a source's disc (centre direction and angular radius, world frame) may reach a
// channel's frustum: its centre or a point just beyond its rim (16 around) lies inside.
// dome_from_world: world -> dome frame for this frame's camera.
bool disc_may_touch_frustum(const ChannelFrustum& frustum, const glm::dmat3& dome_from_world, const GlareFrame& frame,
                            double angular_radius);

}  // namespace cupola

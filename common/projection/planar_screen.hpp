#pragma once
// A flat screen of a VR wall or a CAVE, given by three of its corners in the room, and the
// channel that fills it for an eye: the generalised off-axis perspective (Kooima 2008). The
// channel's axis is the screen's normal, its edges pass through the screen's edges, so the image
// lies on the screen as the eye would see the scene through it, wherever the eye is.
// The room frame has the dome frame's axes (x right, y up, z toward the back: the front is -z),
// in metres, its origin where the configuration puts it (room.eye_m is the eye in it).
#include <glm/glm.hpp>

#include "projection/channel_frustum.hpp"
#include "projection/dome_frame.hpp"

namespace cupola {

struct PlanarScreen {
    glm::dvec3 lower_left_m{0.0}, upper_left_m{0.0}, upper_right_m{0.0};
};

struct ScreenFrustum {
    EulerDeg orientation;
    FovDeg fov;
};

// The channel for the screen seen from eye_m. Throws std::invalid_argument saying what is wrong:
// a corner on another, corners whose edges are not square (to 0.1 degree), the eye on or behind
// the screen's plane (the side its corners, in order lower-left, upper-left, upper-right, turn
// clockwise from), or an edge more than 89 degrees from the axis.
ScreenFrustum screen_frustum(const PlanarScreen& screen, const glm::dvec3& eye_m);

}  // namespace cupola

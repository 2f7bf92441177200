#pragma once
// Orientation conventions shared by master, slaves and the stitcher.
//
// Camera frame (OpenGL): +X right, +Y up, -Z forward. The master's camera orientation (a dquat)
// maps camera-frame vectors into the world frame.
//
// Dome frame: the untilted dome frame equals the camera frame; the dome apex (fisheye centre)
// is +Y. A dome tilted by `tilt` has its apex rotated from +Y towards the front (-Z) by `tilt`.
//
// Channel orientation is given relative to the dome frame, as in MPCDI / SGCT:
//   yaw   positive turns the view to the right (about -Y),
//   pitch positive raises the view (about +X),
//   roll  positive turns the image clockwise as the viewer sees it (about -Z),
// applied as R = R_yaw * R_pitch * R_roll (intrinsic yaw, then pitch, then roll).
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace cupola {

struct EulerDeg {
    double yaw_deg = 0.0;
    double pitch_deg = 0.0;
    double roll_deg = 0.0;
};

// Rotation taking channel-frame vectors to dome-frame vectors.
glm::dmat3 channel_rotation(const EulerDeg& e);
// The yaw, pitch and roll of a rotation (channel frame to dome frame): channel_rotation(euler_of(m))
// is m. Pitch in [-90, 90], yaw and roll in (-180, 180].
EulerDeg euler_of(const glm::dmat3& channel_to_dome);

// Rotation taking dome-frame vectors to camera-frame vectors (apex tilted forward by tilt_deg).
glm::dmat3 dome_tilt_rotation(double tilt_deg);

}  // namespace cupola

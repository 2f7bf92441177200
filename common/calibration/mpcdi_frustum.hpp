#pragma once
// MPCDI's 3d-profile <frustum> (VESA MPCDI v2.0 (2015): yaw, pitch, roll applied yaw
// first, then pitch, then roll; rightAngle, leftAngle, upAngle, downAngle in degrees, signed from
// the view axis, so leftAngle and downAngle are negative for a frustum around its axis) and
// Cupola's channel orientation and half-angles (common/projection/dome_frame.hpp,
// channel_frustum.hpp), both ways:
//   yaw_deg = yaw, pitch_deg = pitch, roll_deg = roll (dome_frame.hpp states MPCDI's order and
//   signs: yaw to the right, pitch up, roll clockwise as seen by the viewer);
//   right_deg = rightAngle, left_deg = -leftAngle, up_deg = upAngle, down_deg = -downAngle.
#include <string>

#include "calibration/projector_warp.hpp"

namespace cupola {

struct MpcdiFrustumAngles {
    double yaw = 0.0, pitch = 0.0, roll = 0.0;
    double right_angle = 45.0, left_angle = -45.0, up_angle = 45.0, down_angle = -45.0;
};

// Throws CalibrationError (naming `name` and the field) for an empty or inverted frustum
// (rightAngle <= leftAngle or upAngle <= downAngle, e.g. a file giving leftAngle as a positive
// magnitude) or angles beyond +-89.9 degrees.
CalibratedFrustum frustum_from_mpcdi(const MpcdiFrustumAngles& angles, const std::string& name);
MpcdiFrustumAngles frustum_to_mpcdi(const CalibratedFrustum& frustum);

}  // namespace cupola

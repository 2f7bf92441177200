#include "calibration/mpcdi_frustum.hpp"

#include <cmath>

#include "calibration/calibration_error.hpp"

namespace cupola {

namespace {
void check_angle(double v, const std::string& name, const char* field) {
    if (!std::isfinite(v) || std::abs(v) > 89.9)
        throw CalibrationError(name, std::string("frustum ") + field, "must be a number within +-89.9 degrees");
}
}  // namespace

CalibratedFrustum frustum_from_mpcdi(const MpcdiFrustumAngles& a, const std::string& name) {
    for (double v : {a.yaw, a.pitch, a.roll})
        if (!std::isfinite(v)) throw CalibrationError(name, "frustum yaw/pitch/roll", "not a number");
    check_angle(a.right_angle, name, "rightAngle");
    check_angle(a.left_angle, name, "leftAngle");
    check_angle(a.up_angle, name, "upAngle");
    check_angle(a.down_angle, name, "downAngle");
    if (a.right_angle <= a.left_angle)
        throw CalibrationError(name, "frustum leftAngle",
                               "rightAngle must exceed leftAngle (the left edge is a negative angle)");
    if (a.up_angle <= a.down_angle)
        throw CalibrationError(name, "frustum downAngle",
                               "upAngle must exceed downAngle (the bottom edge is a negative angle)");
    CalibratedFrustum f;
    f.orientation = EulerDeg{a.yaw, a.pitch, a.roll};
    f.fov = FovDeg{-a.left_angle, a.right_angle, a.up_angle, -a.down_angle};
    return f;
}

MpcdiFrustumAngles frustum_to_mpcdi(const CalibratedFrustum& f) {
    return MpcdiFrustumAngles{f.orientation.yaw_deg, f.orientation.pitch_deg, f.orientation.roll_deg,
                              f.fov.right_deg,       -f.fov.left_deg,         f.fov.up_deg,
                              -f.fov.down_deg};
}

}  // namespace cupola

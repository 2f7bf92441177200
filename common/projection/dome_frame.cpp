#include "projection/dome_frame.hpp"

#include <algorithm>
#include <cmath>

namespace cupola {

namespace {
glm::dmat3 rot_x(double a) {
    double c = std::cos(a), s = std::sin(a);
    // Column-major: columns are the images of the basis vectors.
    return glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, c, s), glm::dvec3(0, -s, c));
}
glm::dmat3 rot_y(double a) {
    double c = std::cos(a), s = std::sin(a);
    return glm::dmat3(glm::dvec3(c, 0, -s), glm::dvec3(0, 1, 0), glm::dvec3(s, 0, c));
}
glm::dmat3 rot_z(double a) {
    double c = std::cos(a), s = std::sin(a);
    return glm::dmat3(glm::dvec3(c, s, 0), glm::dvec3(-s, c, 0), glm::dvec3(0, 0, 1));
}
}  // namespace

glm::dmat3 channel_rotation(const EulerDeg& e) {
    return rot_y(-glm::radians(e.yaw_deg)) * rot_x(glm::radians(e.pitch_deg)) * rot_z(-glm::radians(e.roll_deg));
}

EulerDeg euler_of(const glm::dmat3& m) {
    const glm::dvec3 forward = -m[2];  // (cos p sin y, sin p, -cos p cos y)
    EulerDeg e;
    e.pitch_deg = glm::degrees(std::asin(std::clamp(forward.y, -1.0, 1.0)));
    e.yaw_deg = glm::degrees(std::atan2(forward.x, -forward.z));
    // What is left after yaw and pitch is the roll about the axis: R_roll = (R_yaw R_pitch)^T m.
    const glm::dmat3 roll = glm::transpose(rot_y(-glm::radians(e.yaw_deg)) * rot_x(glm::radians(e.pitch_deg))) * m;
    e.roll_deg = -glm::degrees(std::atan2(roll[0].y, roll[0].x));
    return e;
}

glm::dmat3 dome_tilt_rotation(double tilt_deg) { return rot_x(-glm::radians(tilt_deg)); }

}  // namespace cupola

#include "projection/dome_frame.hpp"

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

glm::dmat3 dome_tilt_rotation(double tilt_deg) { return rot_x(-glm::radians(tilt_deg)); }

}  // namespace cupola

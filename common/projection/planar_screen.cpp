#include "projection/planar_screen.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace cupola {

namespace {
constexpr double kMaxEdgeDeg = 89.0;
constexpr double kSquareCos = 0.0017453;  // cos(89.9 degrees): the edges square to 0.1 degree
}  // namespace

ScreenFrustum screen_frustum(const PlanarScreen& s, const glm::dvec3& eye_m) {
    const glm::dvec3 across = s.upper_right_m - s.upper_left_m, down = s.lower_left_m - s.upper_left_m;
    if (!(glm::length(across) > 1e-6) || !(glm::length(down) > 1e-6))
        throw std::invalid_argument("the screen's corners coincide (its width or height is zero)");
    // The screen's right, up and normal (toward the eye), Kooima 2008's v_r, v_u and v_n.
    const glm::dvec3 right = glm::normalize(across), up = -glm::normalize(down);
    if (std::abs(glm::dot(right, up)) > kSquareCos)
        throw std::invalid_argument("the screen's corners do not make a rectangle: its edges meet at " +
                                    std::to_string(glm::degrees(std::acos(glm::dot(right, up)))) + " degrees");
    const glm::dvec3 normal = glm::normalize(glm::cross(right, up));
    // From the eye to the lower-left, lower-right and upper-left corners.
    const glm::dvec3 lower_left = s.lower_left_m - eye_m, lower_right = lower_left + across,
                     upper_left = s.upper_left_m - eye_m;
    const double distance = -glm::dot(lower_left, normal);
    if (!(distance > 1e-6))
        throw std::invalid_argument("the eye is " + std::string(distance < 0.0 ? "behind" : "on") +
                                    " the screen's plane (it must face the eye; its corners go lower-left, "
                                    "upper-left, upper-right)");
    ScreenFrustum f;
    f.orientation = euler_of(glm::dmat3(right, up, normal));
    f.fov.left_deg = glm::degrees(std::atan(-glm::dot(right, lower_left) / distance));
    f.fov.right_deg = glm::degrees(std::atan(glm::dot(right, lower_right) / distance));
    f.fov.down_deg = glm::degrees(std::atan(-glm::dot(up, lower_left) / distance));
    f.fov.up_deg = glm::degrees(std::atan(glm::dot(up, upper_left) / distance));
    for (const double edge : {f.fov.left_deg, f.fov.right_deg, f.fov.down_deg, f.fov.up_deg})
        if (std::abs(edge) > kMaxEdgeDeg)
            throw std::invalid_argument("an edge of the screen is " + std::to_string(std::abs(edge)) +
                                        " degrees from its axis seen from the eye (at most 89)");
    return f;
}

}  // namespace cupola

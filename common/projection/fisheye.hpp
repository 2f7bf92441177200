#pragma once
// Angular (f-theta) fisheye, Paul Bourke's domemaster convention: the image centre is the dome
// apex, the radius is proportional to the angle from the apex (the image circle is fov_deg wide,
// 180 by default), the front of the dome is at the bottom of the image and the audience's right
// is on the right. Directions are in the (untilted) dome frame of dome_frame.hpp.
#include <glm/glm.hpp>

#include <optional>

namespace cupola {

class FisheyeMapping {
public:
    explicit FisheyeMapping(double fov_deg = 180.0) : half_fov_rad_(glm::radians(fov_deg) * 0.5) {}

    // Normalised image coordinates (u right, v up, both in [-1,1], radius 1 = rim) to a unit
    // dome direction; nothing outside the image circle.
    std::optional<glm::dvec3> uv_to_direction(const glm::dvec2& uv) const;

    // Unit dome direction to normalised image coordinates; nothing beyond the fov.
    std::optional<glm::dvec2> direction_to_uv(const glm::dvec3& dir) const;

    // Pixel (continuous, y down, size x size image) <-> normalised coordinates.
    static glm::dvec2 pixel_to_uv(const glm::dvec2& pixel, int size);
    static glm::dvec2 uv_to_pixel(const glm::dvec2& uv, int size);

    double half_fov_rad() const { return half_fov_rad_; }

private:
    double half_fov_rad_;
};

}  // namespace cupola

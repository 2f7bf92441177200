#pragma once
// One projector channel's view: an orientation in the dome frame and an asymmetric field of view
// given by four angles (left, right, up, down), as MPCDI and SGCT describe a projector frustum.
#include <glm/glm.hpp>

#include <optional>

#include "projection/dome_frame.hpp"

namespace cupola {

struct FovDeg {
    double left_deg = 45.0;
    double right_deg = 45.0;
    double up_deg = 45.0;
    double down_deg = 45.0;
};

class ChannelFrustum {
public:
    ChannelFrustum(const EulerDeg& orientation, const FovDeg& fov, int width, int height);

    // OpenGL projection matrix (glFrustum form) for the given near and far planes.
    glm::dmat4 projection(double near_plane, double far_plane) const;

    // Channel frame -> dome frame.
    const glm::dmat3& rotation() const { return rotation_; }

    // Continuous pixel coordinates (x right, y down, (0,0) = top-left corner of the top-left pixel)
    // of a dome-frame direction, or nothing when the direction is behind the projector plane.
    // Coordinates outside [0,width]x[0,height] mean the direction is outside the frustum.
    std::optional<glm::dvec2> dome_direction_to_pixel(const glm::dvec3& dome_dir) const;

    // Unit dome-frame direction through continuous pixel coordinates (inverse of the above).
    glm::dvec3 pixel_to_dome_direction(const glm::dvec2& pixel) const;

    bool contains(const glm::dvec3& dome_dir) const;

    // Distance, in pixels, from a pixel position to the nearest image edge (negative outside).
    double edge_distance_px(const glm::dvec2& pixel) const;

    // Solid angle per pixel (steradian) at a pixel position: what a star's flux is spread over.
    double pixel_solid_angle(const glm::dvec2& pixel) const;

    int width() const { return width_; }
    int height() const { return height_; }
    const FovDeg& fov() const { return fov_; }
    const EulerDeg& orientation() const { return orientation_; }
    double tan_left() const { return tl_; }
    double tan_right() const { return tr_; }
    double tan_up() const { return tu_; }
    double tan_down() const { return td_; }

private:
    EulerDeg orientation_;
    FovDeg fov_;
    int width_;
    int height_;
    glm::dmat3 rotation_;
    double tl_, tr_, tu_, td_;
};

}  // namespace cupola

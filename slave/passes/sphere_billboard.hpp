#pragma once
// Geometry shared by the sun and body passes: a sphere seen from the camera, reduced to what the
// GPU needs in float (directions and ratios computed in double) plus a covering billboard.
#include <glm/glm.hpp>

#include <array>

#include "gl/gl_program.hpp"
#include "passes/channel_view.hpp"

namespace cupola {

struct SphereView {
    double distance_m = 0.0;  // camera to centre
    double radius_m = 0.0;
    glm::dvec3 center_dir{0.0};  // unit, channel frame
    double sin_alpha = 0.0;      // R / d (>= 1: camera inside or on the sphere)
    // Viewpoint-oriented billboard in "scaled space": the sphere scaled by kScaledDistance / d,
    // so every body sits at the same distance and angular sizes are exact. Its normal points at
    // the camera position (not along the view axis); a fallback axis keeps it valid at the zenith.
    std::array<glm::vec3, 4> corners{};
    bool fullscreen = false;  // camera too close for a billboard: cover the whole viewport

    static constexpr double kScaledDistance = 100.0;
    static constexpr double kNear = 0.5, kFar = 1.0e5;
};

SphereView make_sphere_view(const ChannelView& view, const glm::dvec3& center_world_m, double radius_m);

// (d, R, d - R, d + R) in metres, differences taken in double: what a shader needs to get the
// camera-to-hit distance without cancellation (sphere_hit_distance in body.frag).
glm::vec4 sphere_distances(const SphereView& sphere);

// Sets u_tangents, u_size, u_center_dir, u_sin_alpha, u_distances_m, u_corners, u_projection,
// u_fullscreen and draws the billboard (a 4-vertex strip from gl_VertexID).
void draw_sphere(const GlProgram& program, const ChannelView& view, const SphereView& sphere);

}  // namespace cupola

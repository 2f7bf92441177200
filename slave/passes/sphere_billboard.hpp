#pragma once
// Geometry shared by the sun, body and atmosphere passes: a sphere seen from the camera, reduced to
// what the GPU needs in float (directions and ratios computed in double) plus what covers it on
// screen: a fan over its cap (passes/cap_cover.hpp), the viewport, or a billboard's corners.
#include <glm/glm.hpp>

#include <array>

#include "gl/gl_program.hpp"
#include "passes/cap_cover.hpp"
#include "passes/channel_view.hpp"

namespace cupola {

struct SphereView {
    double distance_m = 0.0;  // camera to centre
    double radius_m = 0.0;
    glm::dvec3 center_dir{0.0};  // unit, channel frame
    double sin_alpha = 0.0;      // R / d (>= 1: camera inside or on the sphere)
    // What is drawn to cover it: the fan over its cap plus a margin of kCoverMargin_px (the
    // sphere's own view), the viewport (the camera inside or on the sphere), or four corners of
    // a billboard in the plane at kScaledDistance (the glare's squares, glare_pass.cpp).
    enum class Cover { Corners, Viewport, Fan };
    Cover cover = Cover::Corners;
    std::array<glm::vec3, 4> corners{};              // Corners: in scaled space, channel frame
    std::array<glm::vec3, kCapCoverVertices> fan{};  // Fan: unit directions, channel frame
    bool fullscreen() const { return cover == Cover::Viewport; }

    static constexpr double kCoverMargin_px = 2.0;
    static constexpr double kScaledDistance = 100.0;
    static constexpr double kNear = 0.5, kFar = 1.0e5;
};

SphereView make_sphere_view(const ChannelView& view, const glm::dvec3& center_world_m, double radius_m);

// The largest angle a pixel of the channel spans: at the centre of its tangent plane.
double pixel_angle_rad(const ChannelFrustum& frustum);

// The half-angle of a sphere's silhouette cone from sin_alpha = R / d (< 1); asin loses precision
// near 1, so it is taken from the complement.
double sphere_angular_radius_rad(double sin_alpha);

// The cover of the directions that miss the sphere (and 2 px more): the cap of pi - alpha around
// the direction away from its centre; the viewport when that is (nearly) every direction or the
// camera is inside.
SphereView complement_cover(const ChannelView& view, const SphereView& sphere);

// (d, R, d - R, d + R) in metres, differences taken in double: what a shader needs to get the
// camera-to-hit distance without cancellation (sphere_hit_distance in body.frag).
glm::vec4 sphere_distances(const SphereView& sphere);

// Sets u_tangents, u_size, u_center_dir, u_sin_alpha, u_distances_m of the sphere and draws its
// cover (draw_cover).
void draw_sphere(const GlProgram& program, const ChannelView& view, const SphereView& sphere);

// Sets what shaders/sphere.vert reads (u_mode, u_corners or u_fan, u_projection) and draws the
// cover: a 4-vertex strip (corners, viewport) or a 26-vertex fan, all from gl_VertexID.
void draw_cover(const GlProgram& program, const ChannelView& view, const SphereView& cover);

}  // namespace cupola

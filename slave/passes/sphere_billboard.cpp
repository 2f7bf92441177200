#include "passes/sphere_billboard.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cupola {

namespace {
// The largest angle a pixel spans: at the centre of the tangent plane.
double pixel_angle_rad(const ChannelFrustum& f) {
    return std::max((f.tan_left() + f.tan_right()) / f.width(), (f.tan_down() + f.tan_up()) / f.height());
}
}  // namespace

SphereView make_sphere_view(const ChannelView& view, const glm::dvec3& center_world_m, double radius_m) {
    SphereView s;
    const glm::dvec3 rel = view.world_to_channel * (center_world_m - view.camera_position_m);  // double
    s.distance_m = glm::length(rel);
    s.radius_m = radius_m;
    s.cover = SphereView::Cover::Viewport;
    if (s.distance_m <= 0.0) {
        s.center_dir = glm::dvec3(0, 0, -1);
        s.sin_alpha = 2.0;
        return s;
    }
    s.center_dir = rel / s.distance_m;
    s.sin_alpha = radius_m / s.distance_m;
    if (s.sin_alpha >= 1.0) return s;  // inside or on the sphere: every direction may show it
    // The silhouette cone's half-angle; asin loses precision near 1, so from the complement.
    const double alpha = std::atan2(s.sin_alpha, std::sqrt((1.0 - s.sin_alpha) * (1.0 + s.sin_alpha)));
    const CapCover c = cap_cover(s.center_dir, alpha, SphereView::kCoverMargin_px * pixel_angle_rad(*view.frustum));
    if (!c.valid) return s;
    for (size_t i = 0; i < c.directions.size(); ++i) s.fan[i] = glm::vec3(c.directions[i]);
    s.cover = SphereView::Cover::Fan;
    return s;
}

SphereView complement_cover(const ChannelView& view, const SphereView& sphere) {
    SphereView s;
    s.cover = SphereView::Cover::Viewport;
    if (!(sphere.sin_alpha < 1.0)) return s;
    const double alpha = std::atan2(sphere.sin_alpha, std::sqrt((1.0 - sphere.sin_alpha) * (1.0 + sphere.sin_alpha)));
    const CapCover c = cap_cover(-sphere.center_dir, std::numbers::pi - alpha,
                                 SphereView::kCoverMargin_px * pixel_angle_rad(*view.frustum));
    if (!c.valid) return s;
    for (size_t i = 0; i < c.directions.size(); ++i) s.fan[i] = glm::vec3(c.directions[i]);
    s.cover = SphereView::Cover::Fan;
    return s;
}

glm::vec4 sphere_distances(const SphereView& sphere) {
    const double d = sphere.distance_m, r = sphere.radius_m;
    return glm::vec4(static_cast<float>(d), static_cast<float>(r), static_cast<float>(d - r),
                     static_cast<float>(d + r));
}

void draw_sphere(const GlProgram& program, const ChannelView& view, const SphereView& sphere) {
    program.set("u_tangents", view.tangents());
    program.set("u_size", view.size());
    program.set("u_center_dir", glm::vec3(sphere.center_dir));
    program.set("u_sin_alpha", static_cast<float>(std::min(sphere.sin_alpha, 1.0)));
    program.set("u_distances_m", sphere_distances(sphere));
    draw_cover(program, view, sphere);
}

void draw_cover(const GlProgram& program, const ChannelView& view, const SphereView& cover) {
    program.set("u_projection", glm::mat4(view.frustum->projection(SphereView::kNear, SphereView::kFar)));
    switch (cover.cover) {
        case SphereView::Cover::Fan:
            program.set("u_mode", 2);
            program.set("u_fan", cover.fan.data(), kCapCoverVertices);
            glDrawArrays(GL_TRIANGLE_FAN, 0, kCapCoverVertices);
            return;
        case SphereView::Cover::Viewport:
            program.set("u_mode", 1);
            break;
        case SphereView::Cover::Corners:
            program.set("u_mode", 0);
            program.set("u_corners", cover.corners.data(), 4);
            break;
    }
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

}  // namespace cupola

#include "passes/sphere_billboard.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cupola {

double pixel_angle_rad(const ChannelFrustum& f) {
    return std::max((f.tan_left() + f.tan_right()) / f.width(), (f.tan_down() + f.tan_up()) / f.height());
}

double sphere_angular_radius_rad(double sin_alpha) {
    return std::atan2(sin_alpha, std::sqrt((1.0 - sin_alpha) * (1.0 + sin_alpha)));
}

namespace {
// The fan over the cone of cone_rad around a unit axis plus the cover margin, or the viewport
// when no fan covers it.
void set_fan_cover(SphereView& s, const ChannelView& view, const glm::dvec3& axis, double cone_rad) {
    const CapCover c = cap_cover(axis, cone_rad, SphereView::kCoverMargin_px * pixel_angle_rad(*view.frustum));
    s.cover = c.valid ? SphereView::Cover::Fan : SphereView::Cover::Viewport;
    if (c.valid)
        for (size_t i = 0; i < c.directions.size(); ++i) s.fan[i] = glm::vec3(c.directions[i]);
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
    set_fan_cover(s, view, s.center_dir, sphere_angular_radius_rad(s.sin_alpha));
    return s;
}

SphereView complement_cover(const ChannelView& view, const SphereView& sphere) {
    SphereView s;
    s.cover = SphereView::Cover::Viewport;
    if (!(sphere.sin_alpha < 1.0)) return s;
    set_fan_cover(s, view, -sphere.center_dir, std::numbers::pi - sphere_angular_radius_rad(sphere.sin_alpha));
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

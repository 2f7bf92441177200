#include "passes/sphere_billboard.hpp"

#include <cmath>

namespace cupola {

SphereView make_sphere_view(const ChannelView& view, const glm::dvec3& center_world_m, double radius_m) {
    SphereView s;
    const glm::dvec3 rel = view.world_to_channel * (center_world_m - view.camera_position_m);  // double
    s.distance_m = glm::length(rel);
    s.radius_m = radius_m;
    if (s.distance_m <= 0.0) {
        s.center_dir = glm::dvec3(0, 0, -1);
        s.sin_alpha = 2.0;
        s.fullscreen = true;
        return s;
    }
    s.center_dir = rel / s.distance_m;
    s.sin_alpha = radius_m / s.distance_m;
    // Closer than ~1.02 radii the covering billboard would be huge: draw everything instead.
    if (s.sin_alpha > 0.98) {
        s.fullscreen = true;
        return s;
    }
    const double k = SphereView::kScaledDistance;
    const glm::dvec3 c = s.center_dir * k;
    // The silhouette cone (half-angle asin(R/d)) cuts the plane through the centre, normal to
    // the line of sight, in a circle of radius d * tan(alpha); 10 % margin.
    const double half = 1.1 * k * s.sin_alpha / std::sqrt(1.0 - s.sin_alpha * s.sin_alpha);
    const glm::dvec3 w = -s.center_dir;  // billboard normal: towards the camera position
    glm::dvec3 up(0.0, 1.0, 0.0);
    if (std::abs(glm::dot(up, w)) > 0.9) up = glm::dvec3(1.0, 0.0, 0.0);  // fallback axis near the zenith
    const glm::dvec3 e1 = glm::normalize(glm::cross(up, w));
    const glm::dvec3 e2 = glm::cross(w, e1);
    s.corners = {glm::vec3(c - half * e1 - half * e2), glm::vec3(c + half * e1 - half * e2),
                 glm::vec3(c - half * e1 + half * e2), glm::vec3(c + half * e1 + half * e2)};
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
    program.set("u_corners", sphere.corners.data(), 4);
    program.set("u_projection", glm::mat4(view.frustum->projection(SphereView::kNear, SphereView::kFar)));
    program.set("u_fullscreen", sphere.fullscreen ? 1 : 0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

}  // namespace cupola

#include "passes/point_sprite_view.hpp"

#include <cmath>

#include <glm/glm.hpp>

#include "gl/gl_api.hpp"

namespace cupola {

PointSpriteView point_sprite_view(const ChannelFrustum& f) {
    const double ppt_x = f.width() / (f.tan_left() + f.tan_right());
    const double ppt_y = f.height() / (f.tan_down() + f.tan_up());
    const int guard = PointSpriteView::kGuardPx;
    const double gx = guard / ppt_x, gy = guard / ppt_y;
    const ChannelFrustum wide(
        f.orientation(),
        FovDeg{glm::degrees(std::atan(f.tan_left() + gx)), glm::degrees(std::atan(f.tan_right() + gx)),
               glm::degrees(std::atan(f.tan_up() + gy)), glm::degrees(std::atan(f.tan_down() + gy))},
        f.width() + 2 * guard, f.height() + 2 * guard);
    return {wide, ppt_x, ppt_y};
}

void bind_guarded_viewport(const ChannelFrustum& f) {
    const int guard = PointSpriteView::kGuardPx;
    glViewport(-guard, -guard, f.width() + 2 * guard, f.height() + 2 * guard);
}

void unbind_guarded_viewport(const ChannelFrustum& f) { glViewport(0, 0, f.width(), f.height()); }

}  // namespace cupola

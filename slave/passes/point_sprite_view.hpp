#pragma once
// What GL point sprites of a PSF (the stars, the planets' points) are drawn through: the channel's
// frustum widened by a guard band of kGuardPx, so that a sprite whose centre lies just outside the
// channel still spills its light into it, and the pixels per tangent-plane unit that size it.
#include "projection/channel_frustum.hpp"

namespace cupola {

struct PointSpriteView {
    static constexpr int kGuardPx = 16;
    ChannelFrustum wide;
    double px_per_tangent_x = 0.0, px_per_tangent_y = 0.0;
};

PointSpriteView point_sprite_view(const ChannelFrustum& f);

// Sets the viewport to the widened frustum's (guard band outside the channel), and back.
void bind_guarded_viewport(const ChannelFrustum& f);
void unbind_guarded_viewport(const ChannelFrustum& f);

}  // namespace cupola

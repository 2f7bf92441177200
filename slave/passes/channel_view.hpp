#pragma once
// What every pass needs to know about the channel for one frame.
#include <glm/glm.hpp>

#include "projection/channel_frustum.hpp"

namespace cupola {

struct ChannelView {
    const ChannelFrustum* frustum = nullptr;
    glm::dmat3 channel_to_world{1.0};  // camera_orientation * dome tilt * channel orientation
    glm::dmat3 world_to_channel{1.0};
    glm::dvec3 camera_position_m{0.0};
    // Frustum tangents (left, right, down, up) and framebuffer size, for rays from gl_FragCoord.
    glm::vec4 tangents() const {
        return glm::vec4(frustum->tan_left(), frustum->tan_right(), frustum->tan_down(), frustum->tan_up());
    }
    glm::vec2 size() const { return glm::vec2(frustum->width(), frustum->height()); }
};

}  // namespace cupola

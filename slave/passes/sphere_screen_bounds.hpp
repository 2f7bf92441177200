#pragma once
// The pixels of a channel that a sphere can cover: the bounding rectangle of its perspective
// projection (Mara & McGuire 2013, section 3: the tangent lines from the eye to the sphere's
// silhouette in the x-z and y-z planes), one pixel wider on each side, clamped to the channel.
// Conservative: the whole channel when the camera is inside the sphere or the silhouette reaches
// behind the camera. Used as the atmosphere's scissor: no work for pixels that cannot see the shell.
#include <glm/glm.hpp>

#include "projection/channel_frustum.hpp"

namespace cupola {

struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;  // GL window coordinates (row 0 at the bottom)
    bool empty() const { return width <= 0 || height <= 0; }
};

// centre: the sphere's centre in the channel frame (camera at the origin looking along -z), metres.
PixelRect sphere_screen_bounds(const ChannelFrustum& frustum, const glm::dvec3& centre_m, double radius_m);

}  // namespace cupola

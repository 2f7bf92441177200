#pragma once
// The texel grid of the glare's reduced-resolution halo for one channel (glare_halo_pass.hpp).
// Texel j covers the channel's full-resolution pixels [j d, (j + 1) d) counted from the
// channel's axis (the image plane's tangent 0), d = the downsample factor, in x and in y; the
// grid reaches a guard band of texels beyond the channel's edges, so that bilinear upsampling
// never clamps at an edge, and starts at an even texel so that derivatives pair the same texels.
// Channels that share an image plane and its pixel pitch (a wide channel cut into narrow ones)
// therefore place the same texels at the same directions, and a pixel gets the same halo value
// whichever of them draws it.
#include <glm/glm.hpp>

#include "projection/channel_frustum.hpp"

namespace cupola {

struct GlareHaloGrid {
    int downsample = 1;            // full-resolution pixels per texel, per axis
    int first_x = 0, first_y = 0;  // texel index (from the axis) of the grid's first texel
    int width = 0, height = 0;     // texels
    // The grid's outer edges as channel_ray (shared/sphere_view.glsl) takes them: left, right,
    // down, up tangents of the texel edges.
    glm::vec4 tangents{0.0f};
    // Texture coordinate of a full-resolution fragment: gl_FragCoord.xy * map.xy + map.zw.
    glm::vec4 map{0.0f};
    double texel_rad = 0.0;  // the larger angle a texel spans at the channel's axis

    static constexpr int kGuardTexels = 2;

    // Throws std::invalid_argument naming the value when downsample is not 1, 2, 4 or 8.
    static GlareHaloGrid for_channel(const ChannelFrustum& frustum, int downsample);
};

}  // namespace cupola

#include "passes/glare_halo_grid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace cupola {

namespace {

// One axis of the grid: pixels (full resolution), the tangents of the channel's two edges.
struct GridAxis {
    int first = 0, count = 0;
    double low_tangent = 0.0, high_tangent = 0.0;  // as channel_ray takes them (low is negated)
    double map_scale = 0.0, map_offset = 0.0;
    double pitch = 0.0;  // tangent per texel
};

GridAxis grid_axis(int pixels, double tan_low, double tan_high, int d) {
    const double pixel_pitch = (tan_low + tan_high) / pixels;
    // Pixels from the channel's low edge to its axis; an integer when the axis is a pixel edge.
    double axis = tan_low / pixel_pitch;
    if (std::abs(axis - std::round(axis)) < 1e-6) axis = std::round(axis);
    GridAxis a;
    const int first = static_cast<int>(std::floor(-axis / d)) - GlareHaloGrid::kGuardTexels;
    a.first = first - ((first % 2 + 2) % 2);  // even
    const int end = static_cast<int>(std::ceil((pixels - axis) / d)) + GlareHaloGrid::kGuardTexels;
    a.count = end - a.first;
    a.pitch = d * pixel_pitch;
    a.low_tangent = -a.first * a.pitch;
    a.high_tangent = end * a.pitch;
    a.map_scale = 1.0 / (static_cast<double>(d) * a.count);
    a.map_offset = (-axis / d - a.first) / a.count;
    return a;
}

}  // namespace

GlareHaloGrid GlareHaloGrid::for_channel(const ChannelFrustum& f, int downsample) {
    if (downsample != 1 && downsample != 2 && downsample != 4 && downsample != 8)
        throw std::invalid_argument("glare halo grid: downsample " + std::to_string(downsample) +
                                    " is not 1, 2, 4 or 8");
    const GridAxis x = grid_axis(f.width(), f.tan_left(), f.tan_right(), downsample);
    const GridAxis y = grid_axis(f.height(), f.tan_down(), f.tan_up(), downsample);
    GlareHaloGrid g;
    g.downsample = downsample;
    g.first_x = x.first;
    g.first_y = y.first;
    g.width = x.count;
    g.height = y.count;
    g.tangents = glm::vec4(x.low_tangent, x.high_tangent, y.low_tangent, y.high_tangent);
    g.map = glm::vec4(x.map_scale, y.map_scale, x.map_offset, y.map_offset);
    g.texel_rad = std::atan(std::max(x.pitch, y.pitch));
    return g;
}

}  // namespace cupola

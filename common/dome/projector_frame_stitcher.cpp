#include "dome/projector_frame_stitcher.hpp"

#include <cmath>
#include <stdexcept>

#include "calibration/mesh_resampling.hpp"
#include "dome/domemaster_stitcher.hpp"

namespace cupola {

namespace {

// The calibration as a mesh in content space: node (i, j) at the grid point's (u, v), valued with
// the projector pixel position of that grid point (fill layout, projector_warp.hpp).
NodeMesh inverse_mesh(const ProjectorWarp& warp) {
    const WarpGrid& g = warp.grid;
    NodeMesh mesh;
    mesh.columns = g.columns;
    mesh.rows = g.rows;
    for (int j = 0; j < g.rows; ++j)
        for (int i = 0; i < g.columns; ++i) {
            mesh.position.push_back(g.uv[static_cast<size_t>(j) * g.columns + i]);
            mesh.value.emplace_back(grid_point_pixel(i, j, g.columns, g.rows, warp.raster_width, warp.raster_height),
                                    0.0);
        }
    return mesh;
}

}  // namespace

Image projector_frame_to_channel(const ProjectorWarp& warp, const Image& projector_frame, int channel_width,
                                 int channel_height) {
    if (projector_frame.width != warp.raster_width || projector_frame.height != warp.raster_height)
        throw std::invalid_argument(warp.source + ": the projector frame is " + std::to_string(projector_frame.width) +
                                    "x" + std::to_string(projector_frame.height) + ", the calibration's raster " +
                                    std::to_string(warp.raster_width) + "x" + std::to_string(warp.raster_height));
    // Channel pixel centre (x, y), row 0 at the top, is content (u, v) = ((x+0.5)/W, 1-(y+0.5)/H).
    const auto projector_px =
        resample_mesh(inverse_mesh(warp), channel_width, channel_height,
                      {0.5 / channel_width, 1.0 - 0.5 / channel_height}, {1.0 / channel_width, -1.0 / channel_height});
    Image out;
    out.width = channel_width;
    out.height = channel_height;
    out.rgba.assign(static_cast<size_t>(channel_width) * channel_height * 4, 0.0f);
    for (int y = 0; y < channel_height; ++y)
        for (int x = 0; x < channel_width; ++x) {
            const glm::dvec3 p = projector_px[static_cast<size_t>(y) * channel_width + x];
            if (std::isnan(p.x) || std::isnan(p.y)) continue;
            float* o = out.pixel(x, y);
            sample_bilinear(projector_frame, p.x, p.y, o);
            o[3] = 1.0f;
        }
    return out;
}

}  // namespace cupola

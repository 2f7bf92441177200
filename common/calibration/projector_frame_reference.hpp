#pragma once
// What a projector shows, computed on the CPU from a ProjectorWarp (projector_warp.hpp) and the
// channel's render: the reference the calibration checks compare against (tests/test_ideal_dome,
// tools/mpcdi_gen). The GPU pass that does this on the render nodes is slave/output/warp_pass.
//
// Between grid points the warp is bilinear; between the outer grid points and the raster's edge
// (half a cell) the position is clamped to the outer point centres. A raster position with a NaN
// among its four grid corners, or a (u, v) outside [0,1], shows black (as reference_warp.hpp). The grid's per-point
// intensity (Bourke meshes) is not applied here: the ideal dome's calibrations carry none.
#include <optional>

#include <glm/glm.hpp>

#include "calibration/projector_warp.hpp"
#include "image/frame_image.hpp"

namespace cupola {

// Content (u, v) (v up) at a continuous raster position, or nothing where the warp shows nothing.
std::optional<glm::dvec2> sample_warp_grid(const ProjectorWarp& warp, const glm::dvec2& pixel);

// A blend map's value at a raster position (bilinear, clamped at the map's edge); fallback when
// the map is empty.
double sample_blend_map(const BlendMap& map, int raster_width, int raster_height, const glm::dvec2& pixel,
                        double fallback);

struct ProjectorFrameOptions {
    bool blend = true;      // apply alpha and beta; false: the naive output, alpha 1 and beta 0
    int quantize_bits = 8;  // the encoded values are rounded to this many bits (0: not rounded)
};

// The projector raster (RGBA, encoded for the projector: value = C_out^(1 / projector_gamma),
// C_out = C alpha (1 - beta) + beta) for a linear-light channel render (row 0 at the top).
Image reference_projector_frame(const ProjectorWarp& warp, const Image& channel_render,
                                const ProjectorFrameOptions& options);

}  // namespace cupola

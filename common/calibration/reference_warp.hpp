#pragma once
// The warp and blend of projector_warp.hpp computed per projector pixel in double on the CPU: the
// ground truth the GPU warp pass and tools/mpcdi_reference.py are compared with. Per projector
// pixel centre: the grid's (u, v) by bilinear interpolation between the four nearest grid points
// (clamped at the outer point centres); black when one of them is NaN or the (u, v) is outside
// [0,1]^2; else the content sampled bilinearly at (u, v) (v up), times alpha * intensity * (1 -
// beta), plus beta (alpha and beta resampled bilinearly onto the raster). Linear light, no encode.
#include <vector>

#include "calibration/projector_warp.hpp"

namespace cupola {

struct LinearImage {
    int width = 0;
    int height = 0;
    int channels = 3;
    std::vector<float> data;  // row 0 at the TOP, interleaved
};

// The content's (u, v) at a continuous projector pixel position (x right, y down, pixel centres at
// +0.5); NaN when not shown.
glm::dvec2 warp_uv_at(const ProjectorWarp& warp, double x_px, double y_px);

// The projector raster (raster_width x raster_height, content.channels) in linear light.
LinearImage reference_warp(const ProjectorWarp& warp, const LinearImage& content);

}  // namespace cupola

#pragma once
// What a projector shows, encoded for it: the CPU reference warp (calibration/reference_warp.hpp:
// the grid's (u, v) bilinear between grid points, clamped at the outer point centres, black at a
// NaN corner or a (u, v) outside [0,1]; C_out = C alpha intensity (1 - beta) + beta, linear) followed
// by the projector's encode gamma, value = C_out^(1 / projector_gamma), rounded to the output's bits.
// The checks of the ideal dome (calibration/ideal_dome_checks.hpp, tools/mpcdi_gen) use it.
#include <optional>

#include <glm/glm.hpp>

#include "calibration/projector_warp.hpp"
#include "image/frame_image.hpp"

namespace cupola {

// Content (u, v) (v up) at a continuous raster position, or nothing where the warp shows nothing.
std::optional<glm::dvec2> sample_warp_grid(const ProjectorWarp& warp, const glm::dvec2& pixel);

struct ProjectorFrameOptions {
    bool blend = true;      // apply alpha and beta; false: the naive output, alpha 1 and beta 0
    int quantize_bits = 8;  // the encoded values are rounded to this many bits (0: not rounded)
};

// The projector raster (RGBA, encoded for the projector, row 0 at the top) for a linear-light
// channel render (row 0 at the top).
Image reference_projector_frame(const ProjectorWarp& warp, const Image& channel_render,
                                const ProjectorFrameOptions& options);

}  // namespace cupola

#pragma once
// Checks of a calibration of ideal projectors (common/calibration/ideal_dome.hpp) against the
// analytic model: what tests/test_ideal_dome asserts and tools/mpcdi_gen reports.
#include <vector>

#include "calibration/ideal_dome.hpp"
#include "calibration/projector_frame_reference.hpp"
#include "calibration/projector_warp.hpp"

namespace cupola {

// Warp geometry: at every projector pixel centre that lights the screen, the dome direction the
// warp shows (grid -> (u, v) -> channel pixel -> ChannelFrustum::pixel_to_dome_direction) against
// the projector's analytic ray, the angle between them in projector pixels (divided by
// IdealProjector::pixel_angle_rad there).
struct WarpGeometryError {
    size_t pixels = 0;     // pixel centres that light the screen
    size_t not_shown = 0;  // of those, where the warp shows nothing (a NaN corner)
    double median_px = 0.0;
    double p99_px = 0.0;
    double max_px = 0.0;
};
WarpGeometryError measure_warp_geometry(const std::vector<IdealProjector>& projectors,
                                        const std::vector<ProjectorWarp>& warps);

// Blend: the projector frames of a uniform white channel render (reference_projector_frame),
// stitched back onto the dome (projector_stitch), sampled at directions on a samples x samples
// domemaster grid at least margin_deg above the springline.
struct BlendFlatness {
    size_t samples = 0;
    size_t overlap_samples = 0;  // lit by two projectors or more
    size_t dark_samples = 0;     // lit by none
    double min_light = 0.0;
    double max_light = 0.0;
    double max_deviation = 0.0;          // max |light - 1| over all samples
    double max_overlap_deviation = 0.0;  // the same over the overlaps
};
BlendFlatness measure_blend_flatness(const std::vector<IdealProjector>& projectors,
                                     const std::vector<ProjectorWarp>& warps, const ProjectorFrameOptions& options,
                                     int samples = 256, double margin_deg = 1.0);

// The projector frames of a uniform white channel render.
std::vector<Image> white_field_frames(const std::vector<ProjectorWarp>& warps, const ProjectorFrameOptions& options);

}  // namespace cupola

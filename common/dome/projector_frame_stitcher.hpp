#pragma once
// Projector frames (what a calibrated channel's files sink writes: the projector raster after the
// warp and blend, slave/output/) put back onto the dome through the channel's own calibration:
// the check that the cluster's projectors together show one seamless sky.
//
// The calibration maps projector pixels to the channel render's (u, v); its inverse (the grid cut
// into two triangles per cell and resampled onto the channel's pixels, common/calibration/
// mesh_resampling.hpp) gives, for every channel pixel, the projector pixel that shows it. Each
// projector frame is resampled that way into its channel's frustum, and the channels are SUMMED
// on the dome: the blend (alpha) is already in the light each projector sends, so overlapping
// projectors add up to the sky where the blend is right, and show a bright or dark seam where not
// (sum_domemaster, dome/domemaster_stitcher.hpp).
#include <vector>

#include "calibration/projector_warp.hpp"
#include "config/cluster_config.hpp"
#include "image/frame_image.hpp"

namespace cupola {

// The projector frame (linear light, raster size) seen in its channel's render space
// (channel_width x channel_height): alpha 1 where some projector pixel shows the channel pixel.
Image projector_frame_to_channel(const ProjectorWarp& warp, const Image& projector_frame, int channel_width,
                                 int channel_height);

}  // namespace cupola

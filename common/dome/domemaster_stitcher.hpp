#pragma once
// Domemaster stitching: resamples the channel renders (each with its own projection, in the dome
// frame) into one angular fisheye image (FisheyeMapping, Paul Bourke's convention), blending the
// overlaps with weights that fall smoothly to zero at every channel's image edge.
//
// The dome tilt is already inside the channel renders: the channel frusta are in the dome frame,
// so the stitcher never applies the tilt.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/cluster_config.hpp"
#include "image/frame_image.hpp"
#include "projection/channel_frustum.hpp"

namespace cupola {

// Bilinear sample (RGBA) of an image at continuous pixel coordinates (x right, y down, (0,0) =
// top-left corner of the top-left pixel); pixel centres are at +0.5; clamps at the borders.
void sample_bilinear(const Image& image, double x, double y, float out_rgba[4]);

// The domemaster (size x size): for every pixel centre inside the fisheye circle, the blend of
// every channel that sees its direction, weighted by smoothstep(0, feather_px, edge distance in
// that channel's pixels) and normalised over the channels (feather_px <= 0: equal weights, hard
// edges). Covered pixels have alpha 1; pixels outside the circle, and pixels inside it that no
// channel covers, are black with alpha 0. images[i] belongs to channels[i]; a null image is
// skipped. Throws std::invalid_argument when the sizes disagree.
Image stitch_domemaster(const DomeConfig& dome, const std::vector<ChannelFrustum>& channels,
                        const std::vector<const Image*>& images, int size, double feather_px = 8.0);

// Like stitch_domemaster, but the channels that see a direction are summed, unweighted: for
// images that carry their blend in their light (projector frames put back into their channel's
// render space, dome/projector_frame_stitcher.hpp). A channel pixel with alpha 0 adds nothing.
Image sum_domemaster(const DomeConfig& dome, const std::vector<ChannelFrustum>& channels,
                     const std::vector<const Image*>& images, int size);

// One channel alone remapped into fisheye space: alpha 1 where the channel covers the direction
// (channel.contains), black with alpha 0 elsewhere.
Image remap_channel_to_fisheye(const DomeConfig& dome, const ChannelFrustum& channel, const Image& image, int size);

struct StitchReport {
    std::vector<uint64_t> frames;       // the frame indices stitched, ascending
    std::vector<std::string> written;   // every file written
    std::vector<std::string> problems;  // missing frames, disagreeing hashes, unreadable files...
};

// Stitches in_dir/<channel name>/frame_NNNNNN.{exr,png} (EXR preferred) into
// out_dir/frame_NNNNNN.png (and .exr when config.output.formats has "exr"), metadata channel -1,
// name "dome", with the output exposure of the config. only_frame: just that frame. size 0: the
// config's domemaster_size. Every frame found in any channel is stitched from what exists; each
// missing channel frame, unreadable file, size mismatch or snapshot-hash disagreement is reported
// in problems. A calibrated channel's files are its projector frames: their EXRs are put back
// into the channel's frustum through its calibration and summed (dome/projector_frame_stitcher.hpp).
// Throws std::runtime_error only when an output cannot be written.
StitchReport stitch_run_directory(const ClusterConfig& config, const std::string& in_dir, const std::string& out_dir,
                                  std::optional<uint64_t> only_frame = std::nullopt, int size = 0);

}  // namespace cupola

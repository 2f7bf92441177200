#pragma once
// What cupola-mpcdi-gen writes besides the package: the cluster config whose channels are the
// package's regions, and the images of the calibration (docs/images/dome-4proj-*.png).
#include <string>
#include <vector>

#include "calibration/ideal_dome.hpp"
#include "calibration/projector_warp.hpp"

namespace cupola {

// template_file's fields with its channels replaced: channel k = region k, named after it, whose
// frustum and projector raster come from the package ("calibration": {"mpcdi", "region"}).
void write_calibrated_config(const std::string& template_file, const std::string& out_file,
                             const std::string& mpcdi_file, const std::vector<ProjectorWarp>& warps);

// dome-4proj-alpha.png (the alpha maps, 2 x 2), dome-4proj-frame.png (projector 0's frame of an
// azimuth/elevation test pattern), dome-4proj-stitched.png (every projector's pattern frame
// stitched back onto a domemaster). Returns the paths written.
std::vector<std::string> write_calibration_images(const std::string& dir, const std::vector<IdealProjector>& projectors,
                                                  const std::vector<ProjectorWarp>& warps);

// Stitches projector frames (PNG or EXR, one per projector in order, their values as the projector
// receives them, decoded with each projector's gamma) back onto a size x size domemaster, written
// as a PNG encoded with gamma 2.2 for viewing: the check image of a warp pass's output.
void write_stitched_frames(const std::string& out_file, const std::vector<IdealProjector>& projectors,
                           const std::vector<std::string>& frame_files, const std::vector<double>& gammas, int size);

}  // namespace cupola

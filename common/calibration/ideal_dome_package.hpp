#pragma once
// The ideal dome's calibration (calibration/ideal_dome_warp.hpp) as one MPCDI v2.0 package
// (calibration/mpcdi_writer.hpp): profile 3d (each region carries the frustum of its channel),
// geometry level 2 (grids finer than 32 x 32), colour level 1 (alpha maps, no beta). One buffer,
// one region per projector side by side (region k at x = k / N, width 1 / N): one file is the whole
// display, as a calibration system exports it, and each channel of the cluster config names its
// region. Alpha maps are 16-bit PNGs with gammaEmbedded 2.2 (linear = stored^2.2, VESA MPCDI v2.0
// (2015) §2.5.1.2.4): the 8-bit form would round a projector's alpha near 0 to coarse steps.
#include <string>
#include <vector>

#include "calibration/mpcdi_writer.hpp"
#include "calibration/projector_warp.hpp"

namespace cupola {

MpcdiPackageOut ideal_dome_package(const std::vector<ProjectorWarp>& warps);
MpcdiWriting ideal_dome_writing();

// Writes the package (throws CalibrationError naming the file).
void write_ideal_dome_mpcdi(const std::string& file, const std::vector<ProjectorWarp>& warps);

}  // namespace cupola

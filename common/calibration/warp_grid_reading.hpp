#pragma once
// An MPCDI warp file's grid (VESA MPCDI v2.0 (2015): a PFM whose R and G hold (u, v), B
// an error estimate, NaN where unknown) turned into projector_warp.hpp's WarpGrid under the
// reading switches, and the checks that catch a file read with the wrong switches.
#include <string>

#include "calibration/mpcdi_coordinates.hpp"
#include "calibration/pfm_file.hpp"
#include "calibration/projector_warp.hpp"

namespace cupola {

struct WarpGridReading {
    WarpFileFrame frame;
    WarpDirection direction = WarpDirection::forward;
    int raster_width = 0;  // the region's xResolution, yResolution
    int raster_height = 0;
};

// forward: each grid point's numbers are the content point it shows (file_to_content).
// inverse: the grid lies over the region's content and its numbers are the projector position
// (normalized, y by v_origin) showing each content point; the piecewise-linear map they describe
// is inverted onto a projector grid of the same size (calibration/mesh_resampling.hpp), and
// projector points no content maps to are NaN.
// Throws CalibrationError naming `name`: too few or too many points for the raster, infinite
// values, no shown point, most points outside [0,1]^2, a folded map (see check_warp_grid).
WarpGrid warp_grid_from_pfm(const PfmImage& pfm, const WarpGridReading& reading, const std::string& name);

// The checks alone, on a grid in content coordinates: at least one shown point; at most half of
// the shown points outside [0,1]^2 (by 1e-3); no fold (cells of both orientations, each over 10 %).
void check_warp_grid(const WarpGrid& grid, const std::string& name);

}  // namespace cupola

#pragma once
// The calibration of an ideal projector (common/calibration/ideal_dome.hpp) in the form of
// common/calibration/projector_warp.hpp: the channel frustum that sees its footprint from the
// dome centre, and the warp grid from its raster to that frustum's render.
#include <vector>

#include "calibration/dome_blend.hpp"
#include "calibration/ideal_dome.hpp"
#include "calibration/projector_warp.hpp"

namespace cupola {

// A frustum (orientation and four half-angles) that holds, seen from the dome centre, every
// sphere point the projector's grid shows (footprint_directions), plus margin_deg on each side:
// aimed at the footprint's mean direction, roll 0. Throws std::invalid_argument naming the
// projector when the footprint is too wide for one pinhole frustum (over ~170 degrees).
CalibratedFrustum fit_channel_frustum(const IdealProjector& projector,
                                      const std::vector<glm::dvec3>& footprint_directions, double margin_deg);

// Which grid points a warp needs: those whose raster position lights the screen, and their eight
// neighbours, so that bilinear interpolation has four valid corners for every raster position
// that lights the screen (where the screen's edge is locally straight at the grid's scale).
std::vector<bool> needed_grid_points(const IdealProjector& projector, int columns, int rows);

// Dome directions of the needed grid points (empty optional where a point is not needed).
std::vector<glm::dvec3> needed_grid_directions(const IdealProjector& projector, int columns, int rows);

// The warp grid: at each needed point, the (u, v) (v up, origin bottom left) of the point's dome
// direction in the channel frustum's render; NaN elsewhere.
WarpGrid ideal_warp_grid(const IdealProjector& projector, const ChannelFrustum& channel, int columns, int rows);

// Everything the calibration generator (tools/mpcdi_gen) needs to calibrate a set of projectors.
struct IdealCalibrationSpec {
    IdealDome dome;
    std::vector<ProjectorPlacement> projectors;
    int grid_columns = 64;  // warp grid points across the raster
    int grid_rows = 64;
    int alpha_width = 0;  // alpha map texels; 0: half the raster's (the blend is smooth at that scale)
    int alpha_height = 0;
    BlendRamp ramp;
    double frustum_margin_deg = 2.0;
    double projector_gamma = 2.2;
    std::string source = "ideal dome";  // ProjectorWarp::source is "<source> region <id>"
};

// One ProjectorWarp per projector, in the spec's order: region id = the projector's id, the
// fitted frustum, the warp grid into that frustum's render, the blend's alpha map, no beta.
std::vector<ProjectorWarp> ideal_projector_warps(const IdealCalibrationSpec& spec);

}  // namespace cupola

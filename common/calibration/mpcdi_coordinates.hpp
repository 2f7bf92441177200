#pragma once
// The (u, v) numbers of an MPCDI warp file and the content coordinates of projector_warp.hpp, both
// ways, under the reading switches v_origin and coordinates (docs/MPCDI.md):
//  - v_origin top: the file's v runs down, v_up = 1 - v (applied in the file's own frame);
//  - 2d profile, region-local (PyMPCDI): buffer content U = x + xSize*u, V = y + ySize*v;
//  - 3d profile, buffer-global: the frustum render's u = (U - x) / xSize, v = (V - y) / ySize;
//  - otherwise the numbers are already in the content frame.
// Region y is the region's lower edge, measured up from the buffer's bottom (PyMPCDI's
// rangeMat, applied before its V flip).
#include <glm/glm.hpp>

#include "calibration/mpcdi_reading.hpp"

namespace cupola {

struct WarpFileFrame {
    bool profile_3d = false;
    double x = 0.0, y = 0.0, x_size = 1.0, y_size = 1.0;  // region in the buffer
    VOrigin v_origin = VOrigin::bottom;
    WarpCoordinates coordinates = WarpCoordinates::region;
};

glm::dvec2 file_to_content(const WarpFileFrame& frame, glm::dvec2 file_uv);
glm::dvec2 content_to_file(const WarpFileFrame& frame, glm::dvec2 content_uv);

}  // namespace cupola

#pragma once
// Paul Bourke's warp mesh files (`.data`), as used for spherical-mirror projection and small
// domes (Bourke 2005, "Spherical mirror: a new approach to hemispherical dome projection"; the
// file format on his page "Warp mesh file format"): line 1 an integer mapping type, line 2
// "nx ny", then nx*ny nodes "x y u v i" with x in [-aspect, aspect], y in [-1, 1] (up), u, v in
// [0, 1] into the rendered image (v up), i the node's intensity; a negative i marks a node that is
// not drawn. The file has no raster size: it is a parameter.
#include <string>

#include "calibration/projector_warp.hpp"

namespace cupola {

// Throws CalibrationError naming the file and the line.
ProjectorWarp decode_bourke_mesh(const std::string& text, const std::string& name, int raster_width, int raster_height);
ProjectorWarp read_bourke_mesh(const std::string& path, int raster_width, int raster_height);

}  // namespace cupola

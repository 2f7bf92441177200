#pragma once
// Writes an MPCDI v2.0 package (VESA MPCDI v2.0 (2015): a zip holding mpcdi.xml, one PFM warp
// per region, PNG alpha and beta maps) from ProjectorWarps, under any reading switch
// (calibration/mpcdi_reading.hpp), so a package written with switches S reads back, with S, to
// the same ProjectorWarps. Used by the tests and by the ideal-dome generator in tools/.
#include <string>
#include <vector>

#include "calibration/mpcdi_reading.hpp"
#include "calibration/projector_warp.hpp"

namespace cupola {

struct MpcdiRegionOut {
    std::string id;
    // Placement in the buffer, normalized: x right from the buffer's left edge, y UP from its
    // bottom edge (the v-up content frame of projector_warp.hpp), x_size/y_size the extent.
    double x = 0.0;
    double y = 0.0;
    double x_size = 1.0;
    double y_size = 1.0;
    // raster size = the region's xResolution/yResolution; grid in the contract's frame (2d profile:
    // buffer content; 3d: the frustum render); alpha/beta linear; frustum written in the 3d profile.
    ProjectorWarp warp;
    std::string buffer_id = "buffer0";
};

struct MpcdiPackageOut {
    std::string profile = "2d";  // "2d" | "3d"
    int geometry_level = 1;
    int color_level = 1;   // 1: alpha map; 2: alpha and beta maps
    int buffer_width = 0;  // every buffer's xResolution/yResolution; 0: the widest region raster
    int buffer_height = 0;
    std::vector<MpcdiRegionOut> regions;
};

// How the file is written: the layout of its numbers (the same switches the reader takes) and the
// encodings of its files.
struct MpcdiWriting {
    MpcdiReading layout;  // pfm_rows, v_origin, coordinates
    PfmByteOrder pfm_byte_order = PfmByteOrder::little_endian;
    int map_bit_depth = 8;            // PNG alpha/beta: 8 | 16
    int map_components = 1;           // PNG alpha/beta: 1 | 3 (the value in every channel)
    double gamma_embedded = 1.0;      // alpha stored as linear^(1/gamma_embedded)
    bool v1_level_attribute = false;  // write MPCDI v1's single `level` instead of geometry/color
    bool v1_attribute_case = false;   // write v1's `Xresolution`/`xsize` spelling
};

// Throws CalibrationError naming the file on any failure (zip, PNG, inconsistent input).
void write_mpcdi(const std::string& file, const MpcdiPackageOut& package, const MpcdiWriting& writing);

}  // namespace cupola

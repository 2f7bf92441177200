#pragma once
// Portable float map (PFM) files, as MPCDI stores its warp grids (VESA MPCDI v2.0 (2015),
// citing the netpbm PFM format): a text header "PF" (3 channels) or "Pf" (1), "W H", then a scale
// whose sign gives the byte order of the 32-bit floats that follow (negative: little-endian), then
// W*H*channels floats. netpbm stores the BOTTOM row first; PyMPCDI reads the first row as the top:
// which one a file means is the reader's switch PfmRows (docs/MPCDI.md).
#include <string>
#include <vector>

namespace cupola {

enum class PfmRows { bottom_first, top_first };  // the file's first row is the raster's bottom | top
enum class PfmByteOrder { little_endian, big_endian };

// In memory, whatever the file's order: row 0 is the TOP row, channels interleaved.
struct PfmImage {
    int width = 0;
    int height = 0;
    int channels = 0;         // 1 or 3
    std::vector<float> data;  // width * height * channels

    float at(int x, int y, int c) const { return data[(static_cast<size_t>(y) * width + x) * channels + c]; }
};

// Decodes a PFM held in memory; `name` is named in every error (CalibrationError).
PfmImage decode_pfm(const std::string& bytes, const std::string& name, PfmRows rows);
PfmImage read_pfm_file(const std::string& path, PfmRows rows);

std::string encode_pfm(const PfmImage& image, PfmRows rows, PfmByteOrder order);
void write_pfm_file(const std::string& path, const PfmImage& image, PfmRows rows, PfmByteOrder order);

}  // namespace cupola

// libFuzzer target cupola-fuzz-pfm: the PFM decoder (common/calibration/pfm_file) and the warp
// grid reading on top of it (warp_grid_reading: switches, inverse-map inversion, the checks),
// under hostile input. The first byte picks the switches; the rest is the file.
#include <cstddef>
#include <cstdint>
#include <string>

#include "calibration/calibration_error.hpp"
#include "calibration/warp_grid_reading.hpp"
#include "fuzz_calibration.hpp"

using namespace cupola;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const uint8_t s = data[0];
    const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        const PfmImage img = decode_pfm(bytes, "fuzz.pfm", s & 1 ? PfmRows::top_first : PfmRows::bottom_first);
        if (img.data.size() != static_cast<size_t>(img.width) * img.height * img.channels) fuzz::violated("pfm size");
        WarpGridReading r;
        r.frame = WarpFileFrame{(s & 2) != 0,
                                0.25,
                                0.0,
                                0.5,
                                1.0,
                                s & 4 ? VOrigin::top : VOrigin::bottom,
                                s & 8 ? WarpCoordinates::buffer : WarpCoordinates::region};
        r.direction = s & 16 ? WarpDirection::inverse : WarpDirection::forward;
        r.raster_width = 640;
        r.raster_height = 480;
        const WarpGrid g = warp_grid_from_pfm(img, r, "fuzz.pfm");
        if (g.uv.size() != static_cast<size_t>(g.columns) * g.rows) fuzz::violated("grid size");
    } catch (const CalibrationError&) {}
    return 0;
}

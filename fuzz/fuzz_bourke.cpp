// libFuzzer target cupola-fuzz-bourke: Paul Bourke mesh files (common/calibration/bourke_mesh)
// under hostile input, onto a 64x48 raster.
#include <cstddef>
#include <cstdint>
#include <string>

#include "calibration/bourke_mesh.hpp"
#include "calibration/calibration_error.hpp"
#include "fuzz_calibration.hpp"

using namespace cupola;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        fuzz::check_warp(decode_bourke_mesh(text, "fuzz.data", 64, 48));
    } catch (const CalibrationError&) {}
    return 0;
}

// libFuzzer target cupola-fuzz-mpcdi: MPCDI packages (common/calibration/mpcdi_package) under
// hostile input. The bytes are the zip, opened in memory (libzip's zip_source_buffer_create
// through ZipArchive); every region is read under the default switches and under the opposite
// of each.
#include <cstddef>
#include <cstdint>
#include <string>

#include "calibration/calibration_error.hpp"
#include "calibration/mpcdi_package.hpp"
#include "fuzz_calibration.hpp"

using namespace cupola;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    MpcdiReading other;
    other.pfm_rows = PfmRows::top_first;
    other.v_origin = VOrigin::top;
    other.coordinates = WarpCoordinates::buffer;
    other.warp_direction = WarpDirection::inverse;
    try {
        const MpcdiPackage p = MpcdiPackage::from_bytes(bytes, "fuzz.mpcdi");
        if (p.regions().empty()) fuzz::violated("package without regions");
        for (const MpcdiRegionInfo& r : p.regions())
            for (const MpcdiReading& reading : {MpcdiReading{}, other}) {
                try {
                    fuzz::check_warp(p.read_region(r.id, reading));
                } catch (const CalibrationError&) {}
            }
    } catch (const CalibrationError&) {}
    return 0;
}

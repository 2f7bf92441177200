// libFuzzer target cupola-fuzz-elevation: the elevation file reader (common/terrain/
// elevation_raster) under hostile GeoTIFFs, given to GDAL from memory (/vsimem/). Checked
// invariants (a violation aborts, which libFuzzer reports): the reader opens the file or throws
// ElevationError; an opened raster has a positive sample spacing, min <= max, a finite steepest
// rise, heights that are finite or nothing, and a cache within its bound. ASan/UBSan turn memory
// errors and UB in the reader into crashes (GDAL itself is not instrumented).
#include <gdal.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "terrain/elevation_raster.hpp"

using namespace cupola::terrain;

namespace {
[[noreturn]] void violated(const char* what) {
    std::fprintf(stderr, "invariant violated: %s\n", what);
    std::abort();
}

void check(const ElevationRaster& r) {
    if (!(r.sample_spacing_rad() > 0.0)) violated("the sample spacing is not positive");
    if (!(r.min_height_m() <= r.max_height_m())) violated("min height above max height");
    if (!std::isfinite(r.max_rise_m_per_rad())) violated("the steepest rise is not finite");
    for (double lat = -1.5; lat <= 1.5; lat += 0.37)
        for (double lon = -3.1; lon <= 3.1; lon += 0.53) {
            const auto h = r.height_m(lat, lon);
            if (h && !std::isfinite(*h)) violated("a height is not finite");
        }
    const ElevationCacheStats s = r.cache_stats();
    if (s.bytes > s.bound_bytes && s.blocks > 1) violated("the cache is over its bound");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const bool quiet = [] {
        CPLSetErrorHandler(CPLQuietErrorHandler);
        return true;
    }();
    (void)quiet;
    const char* path = "/vsimem/fuzz.tif";
    VSILFILE* f = VSIFileFromMemBuffer(path, const_cast<GByte*>(data), static_cast<vsi_l_offset>(size), FALSE);
    if (!f) return 0;
    VSIFCloseL(f);
    ElevationRaster::Options o;
    o.cache_bytes = 1 << 16;
    o.block_px = 16;
    o.max_samples = 1 << 16;
    o.drivers = {"GTiff"};
    try {
        const ElevationRaster r(path, o);
        check(r);
    } catch (const ElevationError&) {}
    VSIUnlink(path);
    return 0;
}

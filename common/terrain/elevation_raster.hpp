#pragma once
// Elevation data read through GDAL (GeoTIFF and every raster format GDAL reads): a north-up raster
// in geographic coordinates (degrees of longitude east of Greenwich and latitude), heights in
// metres after the band's scale and offset. Latitudes on an ellipsoid (WGS 84) are geodetic: the
// planetocentric latitudes asked for are converted by its flattening; without one (a sphere, or
// no coordinate system) they are taken as planetocentric. Blocks of the raster are read on demand and kept in
// a cache bounded in bytes, least recently used first out; the cache's size and traffic are
// reported. Safe to call from several threads (one lock around the cache and GDAL).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace cupola::terrain {

// A file that cannot serve as elevation: the message names the file and what is wrong with it.
struct ElevationError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct ElevationCacheStats {
    size_t blocks = 0, bytes = 0, bound_bytes = 0;
    uint64_t hits = 0, misses = 0, evictions = 0;
};

class ElevationRaster {
public:
    struct Options {
        size_t cache_bytes = size_t{64} << 20;  // the bound on the blocks kept
        int block_px = 256;                     // square blocks read at once
        double max_samples = 4e9;               // larger rasters are refused (the scan reads all)
        std::vector<std::string> drivers;       // GDAL drivers allowed to open it; empty: every one
    };
    // Opens and checks the file, and scans it once for its height range and steepest slope
    // (block by block, not kept). Throws ElevationError.
    ElevationRaster(const std::string& path, const Options& options);
    explicit ElevationRaster(const std::string& path) : ElevationRaster(path, Options{}) {}
    ~ElevationRaster();
    ElevationRaster(const ElevationRaster&) = delete;
    ElevationRaster& operator=(const ElevationRaster&) = delete;

    // The height (m) at a planetocentric latitude and east longitude, bilinear between the four
    // nearest sample centres; nothing outside the
    // data's extent or where a sample is the band's no-data value. Throws ElevationError when a
    // block cannot be read.
    std::optional<double> height_m(double lat_rad, double lon_rad) const;

    double sample_spacing_rad() const;  // the larger of a sample's two sides, as arcs
    double min_height_m() const;        // over every valid sample
    double max_height_m() const;
    double max_rise_m_per_rad() const;   // steepest rise between neighbouring samples per arc
    bool covers_all_longitudes() const;  // 360 degrees: sampled across the antimeridian
    ElevationCacheStats cache_stats() const;
    const std::string& path() const;

    // A test hook: every block read waits this long first (a slow disk or network share).
    void set_read_delay(std::chrono::milliseconds delay);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace cupola::terrain

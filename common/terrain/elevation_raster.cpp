#include "terrain/elevation_raster.hpp"

#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <list>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <vector>

namespace cupola::terrain {

namespace {

constexpr double kDegToRad = 0.017453292519943295769;
// No body's relief reaches this far from its reference sphere (Olympus Mons: 22 km): a sample
// beyond it is a unit or scale error in the file.
constexpr double kMaxHeight_m = 100e3;

std::once_flag gdal_registered;

// One block of heights (NaN where no data), in the cache.
struct Block {
    int width = 0, height = 0;
    std::vector<float> h;
};

}  // namespace

struct ElevationRaster::Impl {
    std::string path;
    Options options;
    GDALDatasetH dataset = nullptr;
    GDALRasterBandH band = nullptr;
    int width = 0, height = 0;
    double gt[6] = {0, 1, 0, 0, 0, -1};
    double scale = 1.0, offset = 0.0;
    std::optional<double> no_data;
    double min_m = 0.0, max_m = 0.0, rise_m_per_rad = 0.0;
    bool wraps = false;
    std::chrono::milliseconds delay{0};

    mutable std::mutex mutex;
    mutable std::list<uint64_t> recent;  // most recent first
    mutable std::unordered_map<uint64_t, std::pair<std::list<uint64_t>::iterator, Block>> blocks;
    mutable ElevationCacheStats stats;

    // A sample that is the band's no-data value, or not a number: no height there.
    bool missing(float v) const {
        return !std::isfinite(v) ||
               (no_data && static_cast<double>(v) == static_cast<double>(static_cast<float>(*no_data)));
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw ElevationError("elevation file '" + path + "': " + what);
    }
    void open();
    void check_geotransform();
    void check_coordinates();
    Block read_block(int bx, int by) const;
    const Block& block(int bx, int by) const;
    std::optional<double> sample(int col, int row) const;
    void scan();
};

void ElevationRaster::Impl::open() {
    std::call_once(gdal_registered, [] { GDALAllRegister(); });
    CPLPushErrorHandler(CPLQuietErrorHandler);
    std::vector<const char*> allowed;
    for (const std::string& d : options.drivers) allowed.push_back(d.c_str());
    allowed.push_back(nullptr);
    dataset = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY,
                         options.drivers.empty() ? nullptr : allowed.data(), nullptr, nullptr);
    CPLPopErrorHandler();
    if (!dataset) fail(std::string("GDAL cannot open it (") + CPLGetLastErrorMsg() + ")");
    if (GDALGetRasterCount(dataset) < 1) fail("it has no raster band");
    band = GDALGetRasterBand(dataset, 1);
    width = GDALGetRasterXSize(dataset);
    height = GDALGetRasterYSize(dataset);
    if (static_cast<double>(width) * height > options.max_samples)
        fail("a raster of " + std::to_string(width) + "x" + std::to_string(height) + " samples is larger than " +
             std::to_string(static_cast<long long>(options.max_samples)) + " samples");
    if (width < 2 || height < 2)
        fail("a raster of " + std::to_string(width) + "x" + std::to_string(height) +
             " samples is too small (at least 2x2)");
    int has = 0;
    scale = GDALGetRasterScale(band, &has);
    if (!has || scale == 0.0) scale = 1.0;
    offset = GDALGetRasterOffset(band, &has);
    if (!has) offset = 0.0;
    const double nd = GDALGetRasterNoDataValue(band, &has);
    if (has) no_data = nd;
    check_geotransform();
    check_coordinates();
}

void ElevationRaster::Impl::check_geotransform() {
    if (GDALGetGeoTransform(dataset, gt) != CE_None) fail("it has no geotransform (where its samples lie)");
    for (double v : gt)
        if (!std::isfinite(v)) fail("its geotransform holds a value that is not a finite number");
    if (gt[2] != 0.0 || gt[4] != 0.0) fail("the raster is rotated or sheared (only north-up rasters are read)");
    // From a tenth of a millimetre on the Earth (1e-9 degrees) to the whole circle.
    const auto usable = [](double step) { return std::abs(step) >= 1e-9 && std::abs(step) <= 360.0; };
    if (!(gt[1] > 0.0) || !usable(gt[1]) || !usable(gt[5]))
        fail("the sample size " + std::to_string(gt[1]) + " x " + std::to_string(gt[5]) + " degrees is not usable");
    const double span_lon = gt[1] * width;
    wraps = std::abs(span_lon - 360.0) < 1e-6 * 360.0;
}

// Geographic coordinates only: a projected CRS (UTM, polar stereographic) is refused; without a
// CRS the extent must be one of longitudes and latitudes.
void ElevationRaster::Impl::check_coordinates() {
    OGRSpatialReferenceH srs = GDALGetSpatialRef(dataset);
    if (srs && !OSRIsGeographic(srs))
        fail("its coordinates are projected, not geographic (reproject it, e.g. gdalwarp -t_srs EPSG:4326)");
    const double lon0 = gt[0], lon1 = gt[0] + gt[1] * width;
    const double lat_a = gt[3], lat_b = gt[3] + gt[5] * height;
    if (lon0 < -180.0 - 1e-9 || lon1 > 360.0 + 1e-9 || std::min(lat_a, lat_b) < -90.0 - 1e-9 ||
        std::max(lat_a, lat_b) > 90.0 + 1e-9)
        fail("its extent (longitude " + std::to_string(lon0) + ".." + std::to_string(lon1) + ", latitude " +
             std::to_string(std::min(lat_a, lat_b)) + ".." + std::to_string(std::max(lat_a, lat_b)) +
             ") is not one of degrees");
}

Block ElevationRaster::Impl::read_block(int bx, int by) const {
    if (delay.count() > 0) std::this_thread::sleep_for(delay);
    Block b;
    const int x0 = bx * options.block_px, y0 = by * options.block_px;
    b.width = std::min(options.block_px, width - x0);
    b.height = std::min(options.block_px, height - y0);
    b.h.resize(static_cast<size_t>(b.width) * b.height);
    if (GDALRasterIO(band, GF_Read, x0, y0, b.width, b.height, b.h.data(), b.width, b.height, GDT_Float32, 0, 0) !=
        CE_None)
        fail("cannot read samples " + std::to_string(x0) + ".." + std::to_string(x0 + b.width - 1) + " x " +
             std::to_string(y0) + ".." + std::to_string(y0 + b.height - 1) + " (" + CPLGetLastErrorMsg() + ")");
    for (float& v : b.h) v = missing(v) ? std::nanf("") : static_cast<float>(v * scale + offset);
    return b;
}

// The block, from the cache or read (then the least recently used are dropped past the bound).
const Block& ElevationRaster::Impl::block(int bx, int by) const {
    const uint64_t key = (static_cast<uint64_t>(by) << 32) | static_cast<uint32_t>(bx);
    auto it = blocks.find(key);
    if (it != blocks.end()) {
        ++stats.hits;
        recent.splice(recent.begin(), recent, it->second.first);
        return it->second.second;
    }
    ++stats.misses;
    Block b = read_block(bx, by);
    stats.bytes += b.h.size() * sizeof(float);
    recent.push_front(key);
    auto& entry = blocks.emplace(key, std::make_pair(recent.begin(), std::move(b))).first->second;
    while (stats.bytes > options.cache_bytes && recent.size() > 1) {
        const uint64_t old = recent.back();
        recent.pop_back();
        stats.bytes -= blocks.at(old).second.h.size() * sizeof(float);
        blocks.erase(old);
        ++stats.evictions;
    }
    stats.blocks = blocks.size();
    return entry.second;
}

std::optional<double> ElevationRaster::Impl::sample(int col, int row) const {
    const Block& b = block(col / options.block_px, row / options.block_px);
    const float v = b.h[static_cast<size_t>(row % options.block_px) * b.width + col % options.block_px];
    if (std::isnan(v)) return std::nullopt;
    return v;
}

// One pass over the raster, block row by block row, not cached: the height range and the steepest
// rise between neighbours (along a row, the run is scaled by the cosine of the latitude).
void ElevationRaster::Impl::scan() {
    bool any = false;
    min_m = 1e300;
    max_m = -1e300;
    const double dlon_rad = gt[1] * kDegToRad, dlat_rad = std::abs(gt[5]) * kDegToRad;
    std::vector<float> prev_row;
    for (int y0 = 0; y0 < height; y0 += options.block_px) {
        const int rows = std::min(options.block_px, height - y0);
        std::vector<float> strip(static_cast<size_t>(width) * rows);
        if (GDALRasterIO(band, GF_Read, 0, y0, width, rows, strip.data(), width, rows, GDT_Float32, 0, 0) != CE_None)
            fail("cannot read rows " + std::to_string(y0) + ".." + std::to_string(y0 + rows - 1) + " (" +
                 CPLGetLastErrorMsg() + ")");
        for (int r = 0; r < rows; ++r) {
            const double lat = (gt[3] + gt[5] * (y0 + r + 0.5)) * kDegToRad;
            const double run_lon = dlon_rad * std::max(std::cos(lat), 1e-3);
            float* row = &strip[static_cast<size_t>(r) * width];
            for (int c = 0; c < width; ++c) {
                const bool nd = missing(row[c]);
                row[c] = nd ? std::nanf("") : static_cast<float>(row[c] * scale + offset);
                if (nd) continue;
                if (!(std::abs(row[c]) <= kMaxHeight_m))
                    fail("sample (" + std::to_string(c) + ", " + std::to_string(y0 + r) + ") is " +
                         std::to_string(row[c]) + " m after the band's scale and offset, beyond +-100 km");
                any = true;
                min_m = std::min(min_m, static_cast<double>(row[c]));
                max_m = std::max(max_m, static_cast<double>(row[c]));
                if (c > 0 && !std::isnan(row[c - 1]))
                    rise_m_per_rad = std::max(rise_m_per_rad, std::abs(row[c] - row[c - 1]) / run_lon);
                if (!prev_row.empty() && !std::isnan(prev_row[static_cast<size_t>(c)]))
                    rise_m_per_rad =
                        std::max(rise_m_per_rad, std::abs(row[c] - prev_row[static_cast<size_t>(c)]) / dlat_rad);
            }
            prev_row.assign(row, row + width);
        }
    }
    if (!any) fail("every sample is no-data");
}

ElevationRaster::ElevationRaster(const std::string& path, const Options& options) : impl_(std::make_unique<Impl>()) {
    impl_->path = path;
    impl_->options = options;
    if (options.block_px < 16) impl_->fail("block size " + std::to_string(options.block_px) + " is under 16");
    impl_->stats.bound_bytes = options.cache_bytes;
    try {
        impl_->open();
        impl_->scan();
    } catch (...) {
        if (impl_->dataset) GDALClose(impl_->dataset);
        throw;
    }
}

ElevationRaster::~ElevationRaster() {
    if (impl_ && impl_->dataset) GDALClose(impl_->dataset);
}

std::optional<double> ElevationRaster::height_m(double lat_rad, double lon_rad) const {
    const Impl& m = *impl_;
    double lon_deg = lon_rad / kDegToRad;
    const double lat_deg = lat_rad / kDegToRad;
    const double span = m.gt[1] * m.width;
    if (lon_deg < m.gt[0]) lon_deg += 360.0 * std::ceil((m.gt[0] - lon_deg) / 360.0);
    if (lon_deg >= m.gt[0] + 360.0) lon_deg -= 360.0 * std::floor((lon_deg - m.gt[0]) / 360.0);
    if (!m.wraps && lon_deg > m.gt[0] + span) return std::nullopt;
    const double row_f = (lat_deg - m.gt[3]) / m.gt[5] - 0.5;
    if (row_f < -0.5 || row_f > m.height - 0.5) return std::nullopt;
    const double col_f = (lon_deg - m.gt[0]) / m.gt[1] - 0.5;
    const double r = std::clamp(row_f, 0.0, m.height - 1.0);
    const int r0 = std::min(static_cast<int>(r), m.height - 2);
    const double fr = r - r0;
    int c0 = static_cast<int>(std::floor(col_f));
    double fc = col_f - c0;
    const auto column = [&](int c) {
        return m.wraps ? (c % m.width + m.width) % m.width : std::clamp(c, 0, m.width - 1);
    };
    if (!m.wraps && col_f < 0.0) c0 = 0, fc = 0.0;
    std::lock_guard<std::mutex> lock(m.mutex);
    const auto a = m.sample(column(c0), r0), b = m.sample(column(c0 + 1), r0);
    const auto c = m.sample(column(c0), r0 + 1), d = m.sample(column(c0 + 1), r0 + 1);
    if (!a || !b || !c || !d) return std::nullopt;
    return (1 - fr) * ((1 - fc) * *a + fc * *b) + fr * ((1 - fc) * *c + fc * *d);
}

double ElevationRaster::sample_spacing_rad() const {
    return std::max(impl_->gt[1], std::abs(impl_->gt[5])) * kDegToRad;
}
double ElevationRaster::min_height_m() const { return impl_->min_m; }
double ElevationRaster::max_height_m() const { return impl_->max_m; }
double ElevationRaster::max_rise_m_per_rad() const { return impl_->rise_m_per_rad; }
bool ElevationRaster::covers_all_longitudes() const { return impl_->wraps; }
const std::string& ElevationRaster::path() const { return impl_->path; }

ElevationCacheStats ElevationRaster::cache_stats() const {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->stats;
}

void ElevationRaster::set_read_delay(std::chrono::milliseconds delay) {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->delay = delay;
}

}  // namespace cupola::terrain

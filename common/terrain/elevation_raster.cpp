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
    GDALRasterBandH mask = nullptr;  // a per-dataset or alpha mask band, when the file has one
    int width = 0, height = 0;
    double gt[6] = {0, 1, 0, 0, 0, -1};
    double scale = 1.0, offset = 0.0;
    std::optional<double> no_data;
    double min_m = 0.0, max_m = 0.0, rise_m_per_rad = 0.0;
    bool wraps = false;
    // tan(geodetic latitude) / tan(planetocentric latitude) on the file's ellipsoid: 1 / (1 - f)^2.
    double geodetic_scale = 1.0;
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
    void check_datum(OGRSpatialReferenceH srs);
    std::vector<float> read_window(int x0, int y0, int w, int h) const;
    Block read_block(int bx, int by) const;
    void scan_row(const float* row, int y, const std::vector<float>& above);
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
    const int mask_flags = GDALGetMaskFlags(band);
    if (mask_flags & (GMF_PER_DATASET | GMF_ALPHA)) mask = GDALGetMaskBand(band);
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
    if (srs) check_datum(srs);
    const double lon0 = gt[0], lon1 = gt[0] + gt[1] * width;
    const double lat_a = gt[3], lat_b = gt[3] + gt[5] * height;
    if (lon0 < -180.0 - 1e-9 || lon1 > 360.0 + 1e-9 || std::min(lat_a, lat_b) < -90.0 - 1e-9 ||
        std::max(lat_a, lat_b) > 90.0 + 1e-9)
        fail("its extent (longitude " + std::to_string(lon0) + ".." + std::to_string(lon1) + ", latitude " +
             std::to_string(std::min(lat_a, lat_b)) + ".." + std::to_string(std::max(lat_a, lat_b)) +
             ") is not one of degrees");
}

// Degrees about the Greenwich meridian only; an ellipsoid's latitudes are geodetic, and Cupola's are
// planetocentric (the direction from the body's centre): height_m converts, by the flattening.
void ElevationRaster::Impl::check_datum(OGRSpatialReferenceH srs) {
    const double unit_rad = OSRGetAngularUnits(srs, nullptr);
    if (std::abs(unit_rad - kDegToRad) > 1e-12)
        fail("its angular unit is " + std::to_string(unit_rad) + " rad, not the degree");
    const double meridian = OSRGetPrimeMeridian(srs, nullptr);
    if (meridian != 0.0) fail("its prime meridian is " + std::to_string(meridian) + " degrees from Greenwich");
    OGRErr err = OGRERR_NONE;
    const double inverse_flattening = OSRGetInvFlattening(srs, &err);
    if (err == OGRERR_NONE && inverse_flattening > 1.0) {
        const double one_minus_f = 1.0 - 1.0 / inverse_flattening;
        geodetic_scale = 1.0 / (one_minus_f * one_minus_f);
    }
}

// Heights of a window of the raster, row by row: NaN where the band's no-data value, its mask (a
// per-dataset or alpha mask, where the file has one) or a non-number says there is no height;
// the band's scale and offset applied elsewhere.
std::vector<float> ElevationRaster::Impl::read_window(int x0, int y0, int w, int h) const {
    std::vector<float> v(static_cast<size_t>(w) * h);
    const std::string where = std::to_string(x0) + ".." + std::to_string(x0 + w - 1) + " x " + std::to_string(y0) +
                              ".." + std::to_string(y0 + h - 1);
    if (GDALRasterIO(band, GF_Read, x0, y0, w, h, v.data(), w, h, GDT_Float32, 0, 0) != CE_None)
        fail("cannot read samples " + where + " (" + CPLGetLastErrorMsg() + ")");
    std::vector<uint8_t> valid;
    if (mask) {
        valid.resize(v.size());
        if (GDALRasterIO(mask, GF_Read, x0, y0, w, h, valid.data(), w, h, GDT_Byte, 0, 0) != CE_None)
            fail("cannot read the mask of samples " + where + " (" + CPLGetLastErrorMsg() + ")");
    }
    for (size_t i = 0; i < v.size(); ++i)
        v[i] = missing(v[i]) || (mask && valid[i] == 0) ? std::nanf("") : static_cast<float>(v[i] * scale + offset);
    return v;
}

Block ElevationRaster::Impl::read_block(int bx, int by) const {
    if (delay.count() > 0) std::this_thread::sleep_for(delay);
    Block b;
    const int x0 = bx * options.block_px, y0 = by * options.block_px;
    b.width = std::min(options.block_px, width - x0);
    b.height = std::min(options.block_px, height - y0);
    b.h = read_window(x0, y0, b.width, b.height);
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

// One row's part of the scan: the range, and the steepest rise along the row (the run scaled by
// the cosine of the latitude), to the row above, and across the antimeridian when it wraps.
void ElevationRaster::Impl::scan_row(const float* row, int y, const std::vector<float>& above) {
    const double lat = (gt[3] + gt[5] * (y + 0.5)) * kDegToRad;
    const double run_lon = gt[1] * kDegToRad * std::max(std::cos(lat), 1e-3), run_lat = std::abs(gt[5]) * kDegToRad;
    const auto rise = [&](float a, float b, double run) {
        if (!std::isnan(a) && !std::isnan(b)) rise_m_per_rad = std::max(rise_m_per_rad, std::abs(a - b) / run);
    };
    for (int c = 0; c < width; ++c) {
        if (std::isnan(row[c])) continue;
        if (!(std::abs(row[c]) <= kMaxHeight_m))
            fail("sample (" + std::to_string(c) + ", " + std::to_string(y) + ") is " + std::to_string(row[c]) +
                 " m after the band's scale and offset, beyond +-100 km");
        min_m = std::min(min_m, static_cast<double>(row[c]));
        max_m = std::max(max_m, static_cast<double>(row[c]));
        if (c > 0) rise(row[c], row[c - 1], run_lon);
        if (!above.empty()) rise(row[c], above[static_cast<size_t>(c)], run_lat);
    }
    if (wraps) rise(row[0], row[width - 1], run_lon);
}

// One pass over the raster, a strip of block_px rows at a time, not cached.
void ElevationRaster::Impl::scan() {
    min_m = 1e300;
    max_m = -1e300;
    std::vector<float> above;
    for (int y0 = 0; y0 < height; y0 += options.block_px) {
        const int rows = std::min(options.block_px, height - y0);
        const std::vector<float> strip = read_window(0, y0, width, rows);
        for (int r = 0; r < rows; ++r) {
            const float* row = &strip[static_cast<size_t>(r) * width];
            scan_row(row, y0 + r, above);
            above.assign(row, row + width);
        }
    }
    if (min_m > max_m) fail("every sample is no-data");
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
    const double lat_deg = std::atan2(std::sin(lat_rad) * m.geodetic_scale, std::cos(lat_rad)) / kDegToRad;
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

// cupola-fuzz-elevation-corpus DIR: writes the seeds of cupola-fuzz-elevation with GDAL, small
// GeoTIFFs of the kinds elevation comes in: float and 16-bit integer samples, striped and tiled,
// compressed and not, with a no-data value and a scale, global (0..360) and regional.
#include <gdal.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {
const char* kWgs84 =
    "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],PRIMEM[\"Greenwich\",0],"
    "UNIT[\"degree\",0.0174532925199433]]";

bool write(const std::string& path, int w, int h, GDALDataType type, const std::vector<const char*>& creation,
           double lon0, double lat_top, double step, bool no_data) {
    std::vector<char*> opts;
    for (const char* c : creation) opts.push_back(const_cast<char*>(c));
    opts.push_back(nullptr);
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), w, h, 1, type, opts.data());
    if (!ds) return false;
    double gt[6] = {lon0, step, 0.0, lat_top, 0.0, -step};
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, kWgs84);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    if (no_data) GDALSetRasterNoDataValue(band, -32768.0);
    std::vector<float> v(static_cast<size_t>(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            v[static_cast<size_t>(y) * w + x] =
                (no_data && x == y) ? -32768.0f : static_cast<float>(1000.0 * std::sin(x * 0.3) * std::cos(y * 0.2));
    const bool ok = GDALRasterIO(band, GF_Write, 0, 0, w, h, v.data(), w, h, GDT_Float32, 0, 0) == CE_None;
    GDALClose(ds);
    return ok;
}
}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    GDALAllRegister();
    const std::string dir = argv[1];
    VSIMkdirRecursive(dir.c_str(), 0755);
    bool ok = write(dir + "/float-regional.tif", 24, 16, GDT_Float32, {}, 9.5, 46.0, 0.01, false);
    ok = write(dir + "/int16-nodata-global.tif", 36, 18, GDT_Int16, {"COMPRESS=DEFLATE"}, 0.0, 90.0, 10.0, true) && ok;
    ok = write(dir + "/float-tiled.tif", 40, 40, GDT_Float32, {"TILED=YES", "BLOCKXSIZE=16", "BLOCKYSIZE=16"}, -180.0,
               90.0, 4.5, false) &&
         ok;
    ok = write(dir + "/int16-lzw.tif", 20, 10, GDT_Int16, {"COMPRESS=LZW"}, 100.0, -10.0, 0.5, false) && ok;
    return ok ? 0 : 1;
}

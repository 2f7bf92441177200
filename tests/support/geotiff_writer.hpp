#pragma once
// Small GeoTIFFs the terrain tests write themselves, through GDAL.
#include <gdal.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace cupola::test {

// A GeoTIFF written through GDAL: w x h samples over the given extent (degrees), heights from f.
template <class F>
inline std::string write_geotiff(const std::string& path, int w, int h, double lon0, double lat_top, double step_deg,
                                 F f, bool with_srs = true) {
    GDALAllRegister();
    GDALDriverH drv = GDALGetDriverByName("GTiff");
    GDALDatasetH ds = GDALCreate(drv, path.c_str(), w, h, 1, GDT_Float32, nullptr);
    double gt[6] = {lon0, step_deg, 0.0, lat_top, 0.0, -step_deg};
    GDALSetGeoTransform(ds, gt);
    if (with_srs)
        GDALSetProjection(ds,
                          "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],"
                          "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433]]");
    std::vector<float> v(static_cast<size_t>(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            v[static_cast<size_t>(y) * w + x] =
                static_cast<float>(f(lon0 + (x + 0.5) * step_deg, lat_top - (y + 0.5) * step_deg));
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, w, h, v.data(), w, h, GDT_Float32, 0, 0), CE_None);
    GDALClose(ds);
    return path;
}

// The planetocentric latitude (degrees) of a WGS 84 geodetic one: the files' latitudes are
// geodetic, Cupola's planetocentric.
inline double centric_deg(double geodetic_deg) {
    const double f = 1.0 / 298.257223563, deg = 0.017453292519943295769;
    return std::atan((1 - f) * (1 - f) * std::tan(geodetic_deg * deg)) / deg;
}

}  // namespace cupola::test

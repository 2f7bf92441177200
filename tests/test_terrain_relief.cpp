// The terrain's relief (common/terrain/procedural_relief, elevation_raster, relief): procedural
// detail deterministic and band-limited, elevation files read through GDAL at the right place,
// bad files named, the block cache bounded.
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <fstream>
#include <random>

#include "support/geotiff_writer.hpp"
#include "support/test_support.hpp"
#include "terrain/cube_sphere.hpp"
#include "terrain/elevation_raster.hpp"
#include "terrain/relief.hpp"

using namespace cupola;
using namespace cupola::terrain;

namespace {
constexpr double kDeg = 0.017453292519943295769;

// A cone 2000 m high at (lon 10.25, lat 45.5), 0.5 degrees wide at its base.
double cone(double lon, double lat) {
    const double r = std::hypot(lon - 10.25, lat - 45.5);
    return std::max(0.0, 2000.0 * (1.0 - r / 0.5));
}

std::string expect_error(const std::string& path) {
    try {
        ElevationRaster r(path);
        ADD_FAILURE() << path << " was taken";
    } catch (const ElevationError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(ProceduralRelief, SameHeightEverywhereItIsAskedAndWithinItsBound) {
    ProceduralRelief p;
    std::mt19937_64 rng(5);
    std::normal_distribution<double> n;
    double lo = 0.0, hi = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 d = glm::normalize(glm::dvec3(n(rng), n(rng), n(rng))) * 6371e3;
        const double h = p.height_m(d, 10.0);
        ASSERT_EQ(h, p.height_m(d, 10.0));  // deterministic
        ASSERT_LE(std::abs(h), p.amplitude_bound_m());
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
    // Relief, not flat: it spans a good part of its bound.
    EXPECT_GT(hi - lo, 0.5 * p.amplitude_bound_m());
    ProceduralRelief other = p;
    other.seed = 2;
    EXPECT_NE(p.height_m(glm::dvec3(6371e3, 0, 0), 10.0), other.height_m(glm::dvec3(6371e3, 0, 0), 10.0));
}

TEST(ProceduralRelief, NoiseCurvatureIsWithinTheErrorModelsBound) {
    // mesh_error_m assumes |d2n/dx2| < 16 for unit-lattice gradient noise: measured here.
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-50.0, 50.0);
    double worst = 0.0;
    const double e = 1e-3;
    for (int i = 0; i < 200000; ++i) {
        const glm::dvec3 p(u(rng), u(rng), u(rng));
        const glm::dvec3 random_axis = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
        for (const glm::dvec3& axis : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), random_axis}) {
            const double d2 =
                (gradient_noise(p + e * axis, 3) - 2 * gradient_noise(p, 3) + gradient_noise(p - e * axis, 3)) /
                (e * e);
            worst = std::max(worst, std::abs(d2));
        }
    }
    std::printf("gradient noise: largest second derivative %.2f per unit lattice squared\n", worst);
    EXPECT_LT(worst, 16.0);
}

TEST(ProceduralRelief, AFinerMeshAddsDetailACoarseOneLeavesOut) {
    ProceduralRelief p;
    const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.5, 0.8)) * 6371e3;
    // Spacing 100 km: octaves shorter than 400 km are out; the base (200 km) octave too.
    EXPECT_EQ(p.height_m(d, 100e3), 0.0);
    const double coarse = p.height_m(d, 1000.0), fine = p.height_m(d, 1.0);
    EXPECT_NE(coarse, fine);
    EXPECT_LT(std::abs(coarse - fine), p.mesh_error_m(1000.0));
    EXPECT_GT(p.mesh_error_m(1000.0), p.mesh_error_m(100.0));
}

TEST(ElevationRaster, AConeLiesAtItsLatitudeAndLongitudeWithinOneSample) {
    const std::string dir = test::scratch_dir("terrain_cone");
    const double step = 0.01;
    const std::string file = test::write_geotiff(dir + "/cone.tif", 150, 100, 9.5, 46.0, step, cone);
    const ElevationRaster r(file);
    EXPECT_NEAR(r.sample_spacing_rad(), step * kDeg, 1e-12);
    EXPECT_NEAR(r.max_height_m(), 2000.0, 60.0);
    EXPECT_FALSE(r.covers_all_longitudes());
    // The peak: the highest of the heights on a fine grid lies within one sample of (10.25, 45.5).
    double best = -1.0, best_lon = 0.0, best_lat = 0.0;
    for (double lat = 45.0; lat <= 45.7; lat += 0.002)  // planetocentric: geodetic 45.19..45.89
        for (double lon = 9.6; lon <= 10.9; lon += 0.002) {
            const double h = r.height_m(lat * kDeg, lon * kDeg).value();
            if (h > best) best = h, best_lon = lon, best_lat = lat;
        }
    // The file's latitudes are geodetic (WGS 84); Cupola's are planetocentric, 0.19 degrees less here.
    EXPECT_NEAR(best_lon, 10.25, step);
    EXPECT_NEAR(best_lat, test::centric_deg(45.5), step);
    EXPECT_GT(std::abs(45.5 - test::centric_deg(45.5)), 10 * step);  // the conversion matters at this scale
    // Its flank: within a sample's change of the cone's own height.
    for (double r_deg : {0.1, 0.2, 0.3, 0.4})
        EXPECT_NEAR(r.height_m(test::centric_deg(45.5) * kDeg, (10.25 + r_deg) * kDeg).value(),
                    cone(10.25 + r_deg, 45.5), 2000.0 / 0.5 * step)
            << r_deg;
    // Outside the extent: nothing (the relief falls back to procedural there).
    EXPECT_FALSE(r.height_m(45.5 * kDeg, 12.0 * kDeg).has_value());
    EXPECT_FALSE(r.height_m(47.0 * kDeg, 10.0 * kDeg).has_value());
    // A step's steepest rise is found by the scan.
    EXPECT_NEAR(r.max_rise_m_per_rad(), 2000.0 / (0.5 * kDeg) / std::cos(45.5 * kDeg), 0.35 * 2000.0 / (0.5 * kDeg));
}

TEST(ElevationRaster, AStepIsAtItsLongitudeAndTheReliefPutsItOnTheSphere) {
    const std::string dir = test::scratch_dir("terrain_step");
    const double step = 0.05;
    // A global raster, 0..360 east: 1000 m east of longitude 30, 0 west of it (within 0..180).
    const std::string file = test::write_geotiff(dir + "/step.tif", 7200, 10, 0.0, 0.25, step, [](double lon, double) {
        return lon > 30.0 && lon < 180.0 ? 1000.0 : 0.0;
    });
    auto data = std::make_shared<ElevationRaster>(file);
    EXPECT_TRUE(data->covers_all_longitudes());
    EXPECT_NEAR(data->height_m(0.0, 29.9 * kDeg).value(), 0.0, 1e-9);
    EXPECT_NEAR(data->height_m(0.0, 30.1 * kDeg).value(), 1000.0, 1e-9);
    // West longitudes wrap: -10 is 350.
    EXPECT_NEAR(data->height_m(0.0, -10.0 * kDeg).value(), 0.0, 1e-9);
    ProceduralRelief none;
    none.octaves = 0;
    const Relief relief(6371e3, data, none);
    EXPECT_NEAR(relief.height_m(lat_lon_to_direction(0.0, 30.1 * kDeg), 0.0), 1000.0, 1e-9);
    EXPECT_NEAR(relief.height_m(lat_lon_to_direction(0.0, 29.9 * kDeg), 0.0), 0.0, 1e-9);
}

TEST(ElevationRaster, BadFilesAreNamedAndTheReliefFallsBackToProcedural) {
    const std::string dir = test::scratch_dir("terrain_bad");
    EXPECT_NE(expect_error(dir + "/missing.tif").find("missing.tif': GDAL cannot open it"), std::string::npos);
    { std::ofstream(dir + "/garbage.tif") << "II*\0 this is not a TIFF at all"; }
    EXPECT_NE(expect_error(dir + "/garbage.tif").find("garbage.tif'"), std::string::npos);
    // Projected coordinates are refused with the remedy named.
    {
        GDALAllRegister();
        GDALDatasetH ds =
            GDALCreate(GDALGetDriverByName("GTiff"), (dir + "/utm.tif").c_str(), 4, 4, 1, GDT_Float32, nullptr);
        double gt[6] = {500000.0, 30.0, 0.0, 5000000.0, 0.0, -30.0};
        GDALSetGeoTransform(ds, gt);
        OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(srs, 32632);
        GDALSetSpatialRef(ds, srs);
        OSRDestroySpatialReference(srs);
        GDALClose(ds);
    }
    EXPECT_NE(expect_error(dir + "/utm.tif").find("projected, not geographic"), std::string::npos);
    // No coordinates at all: an extent that is not one of degrees.
    test::write_geotiff(dir + "/metres.tif", 4, 4, 500000.0, 5000000.0, 30.0, cone, false);
    EXPECT_NE(expect_error(dir + "/metres.tif").find("is not one of degrees"), std::string::npos);
    // Heights in the wrong unit (here: millimetres) are refused, naming the sample.
    test::write_geotiff(dir + "/millimetres.tif", 4, 4, 10.0, 46.0, 0.1, [](double, double) { return 2.5e6; });
    EXPECT_NE(expect_error(dir + "/millimetres.tif").find("sample (0, 0) is 2500000"), std::string::npos);
    // What a node does with a bad file: procedural relief, the same on every node.
    ProceduralRelief p;
    const Relief fallback(6371e3, nullptr, p);
    EXPECT_FALSE(fallback.has_data());
    EXPECT_NE(fallback.height_m(lat_lon_to_direction(0.3, 0.2), 10.0), 0.0);
}

TEST(ElevationRaster, AMaskedSampleHasNoHeight) {
    // A file without a no-data value whose voids are in a mask band (as GDAL writes one with
    // GDALCreateMaskBand): masked samples have no height, they are not 0 m.
    const std::string dir = test::scratch_dir("terrain_mask");
    const std::string file =
        test::write_geotiff(dir + "/masked.tif", 20, 10, 10.0, 46.0, 0.1, [](double, double) { return 500.0; });
    {
        GDALDatasetH ds = GDALOpen(file.c_str(), GA_Update);
        ASSERT_NE(ds, nullptr);
        GDALRasterBandH band = GDALGetRasterBand(ds, 1);
        ASSERT_EQ(GDALCreateMaskBand(band, GMF_PER_DATASET), CE_None);
        std::vector<uint8_t> valid(200);
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 20; ++x) valid[static_cast<size_t>(y) * 20 + x] = x < 10 ? 0 : 255;
        ASSERT_EQ(GDALRasterIO(GDALGetMaskBand(band), GF_Write, 0, 0, 20, 10, valid.data(), 20, 10, GDT_Byte, 0, 0),
                  CE_None);
        GDALClose(ds);
    }
    const ElevationRaster r(file);
    const double lat = test::centric_deg(45.5) * kDeg;
    EXPECT_FALSE(r.height_m(lat, 10.5 * kDeg).has_value());  // masked (west half)
    EXPECT_NEAR(r.height_m(lat, 11.5 * kDeg).value(), 500.0, 1e-9);
    EXPECT_EQ(r.min_height_m(), 500.0);
}

TEST(ElevationRaster, TheBlockCacheStaysWithinItsBound) {
    const std::string dir = test::scratch_dir("terrain_cache");
    const std::string file = test::write_geotiff(
        dir + "/big.tif", 1024, 512, 0.0, 90.0, 360.0 / 1024,
        [](double lon, double lat) { return 100.0 * std::sin(lon * kDeg * 3) * std::cos(lat * kDeg); });
    ElevationRaster::Options o;
    o.block_px = 64;
    o.cache_bytes = 20 * 64 * 64 * sizeof(float);  // 20 blocks of the 128
    const ElevationRaster r(file, o);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> lat(-1.5, 1.5), lon(-3.1, 3.1);
    for (int i = 0; i < 5000; ++i) r.height_m(lat(rng), lon(rng));
    const ElevationCacheStats s = r.cache_stats();
    std::printf("elevation cache: %zu blocks, %zu of %zu bytes, %llu hits, %llu misses, %llu evictions\n", s.blocks,
                s.bytes, s.bound_bytes, static_cast<unsigned long long>(s.hits),
                static_cast<unsigned long long>(s.misses), static_cast<unsigned long long>(s.evictions));
    EXPECT_LE(s.bytes, o.cache_bytes);
    EXPECT_EQ(s.blocks, 20u);
    EXPECT_GT(s.evictions, 0u);
    EXPECT_EQ(s.hits + s.misses, 5000u * 4);  // four samples per height
    // A block evicted and read again gives the same heights.
    const auto before = r.height_m(0.3, 0.4);
    const uint64_t misses = r.cache_stats().misses;
    for (double lat : {-1.3, -0.9})  // 32 other blocks: more than the cache holds, so it is evicted
        for (int k = 0; k < 32; ++k) r.height_m(lat, -3.1 + 0.19 * k);
    const uint64_t misses_elsewhere = r.cache_stats().misses;
    EXPECT_EQ(r.height_m(0.3, 0.4), before);
    EXPECT_GT(misses_elsewhere, misses);
    EXPECT_GT(r.cache_stats().misses, misses_elsewhere);  // it was read again, not found in the cache
}

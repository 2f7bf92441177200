// cupola-fuzz-calibration-corpus DIR: writes seed inputs for the calibration fuzzers with the
// writers under test (so they follow the current format): DIR/mpcdi-*.mpcdi (2d and 3d
// profiles, blend maps, v1 attributes, big-endian PFM) and DIR/pfm-* (a switch byte + a PFM).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "calibration/mpcdi_writer.hpp"

using namespace cupola;

namespace {

MpcdiPackageOut package(bool profile_3d) {
    MpcdiPackageOut p;
    p.profile = profile_3d ? "3d" : "2d";
    p.color_level = 2;
    MpcdiRegionOut r;
    r.id = "r0";
    r.x_size = profile_3d ? 1.0 : 0.5;
    r.warp.raster_width = 16;
    r.warp.raster_height = 12;
    r.warp.grid = WarpGrid{4, 3, {}, {}};
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) r.warp.grid.uv.emplace_back(r.x_size * (i + 0.5) / 4, 1.0 - (j + 0.5) / 3);
    r.warp.grid.uv[0] = glm::dvec2(std::nan(""));
    r.warp.alpha = BlendMap{4, 2, {0.1f, 0.5f, 1.0f, 1.0f, 0.2f, 0.4f, 0.6f, 0.8f}};
    r.warp.beta = BlendMap{2, 2, {0.0f, 0.01f, 0.02f, 0.03f}};
    if (profile_3d) r.warp.frustum = CalibratedFrustum{EulerDeg{10, 20, 0}, FovDeg{30, 30, 20, 20}};
    p.regions.push_back(r);
    return p;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    std::filesystem::create_directories(dir);
    MpcdiWriting plain;
    MpcdiWriting other;
    other.layout.pfm_rows = PfmRows::top_first;
    other.pfm_byte_order = PfmByteOrder::big_endian;
    other.map_bit_depth = 16;
    other.map_components = 3;
    other.gamma_embedded = 2.2;
    other.v1_level_attribute = true;
    other.v1_attribute_case = true;
    write_mpcdi(dir + "/mpcdi-2d.mpcdi", package(false), plain);
    write_mpcdi(dir + "/mpcdi-3d-v1.mpcdi", package(true), other);
    PfmImage pfm{
        3,
        2,
        3,
        {0.1f, 0.2f, 0.0f, 0.5f, 0.2f, 0.0f, 0.9f, 0.2f, 0.0f, 0.1f, 0.8f, 0.0f, 0.5f, 0.8f, 0.0f, 0.9f, 0.8f, 0.0f}};
    for (int s : {0, 17}) {
        std::ofstream out(dir + "/pfm-" + std::to_string(s), std::ios::binary);
        out << static_cast<char>(s)
            << encode_pfm(pfm, PfmRows::bottom_first, s ? PfmByteOrder::big_endian : PfmByteOrder::little_endian);
    }
    return 0;
}

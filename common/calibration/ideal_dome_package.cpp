#include "calibration/ideal_dome_package.hpp"

#include <algorithm>

namespace cupola {

MpcdiPackageOut ideal_dome_package(const std::vector<ProjectorWarp>& warps) {
    MpcdiPackageOut p;
    p.profile = "3d";
    p.geometry_level = 2;
    p.color_level = 1;
    const double n = static_cast<double>(warps.size());
    for (const auto& w : warps)
        p.buffer_width += w.raster_width, p.buffer_height = std::max(p.buffer_height, w.raster_height);
    for (size_t k = 0; k < warps.size(); ++k) {
        MpcdiRegionOut r;
        r.id = warps[k].region_id;
        r.x = static_cast<double>(k) / n;
        r.y = 0.0;
        r.x_size = 1.0 / n;
        r.y_size = 1.0;
        r.warp = warps[k];
        p.regions.push_back(std::move(r));
    }
    return p;
}

MpcdiWriting ideal_dome_writing() {
    MpcdiWriting w;
    w.map_bit_depth = 16;
    w.gamma_embedded = 2.2;
    return w;
}

void write_ideal_dome_mpcdi(const std::string& file, const std::vector<ProjectorWarp>& warps) {
    write_mpcdi(file, ideal_dome_package(warps), ideal_dome_writing());
}

}  // namespace cupola

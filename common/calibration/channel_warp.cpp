#include "calibration/channel_warp.hpp"

#include "calibration/bourke_mesh.hpp"
#include "calibration/mpcdi_package.hpp"

namespace cupola {

ProjectorWarp load_channel_warp(const ChannelCalibration& c) {
    if (!c.bourke_file.empty()) return read_bourke_mesh(c.bourke_file, c.raster_width, c.raster_height);
    return MpcdiPackage::open(c.mpcdi_file).read_region(c.region, c.reading);
}

}  // namespace cupola

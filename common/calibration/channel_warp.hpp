#pragma once
// A channel's projector warp from its calibration reference in the cluster config
// (channels[].calibration): the MPCDI region under the configured reading switches, or the Paul
// Bourke mesh at the configured raster. What the slave's output stage applies and what the
// loopback's stitcher inverts. Throws CalibrationError naming the file and field.
#include "calibration/projector_warp.hpp"
#include "config/cluster_config.hpp"

namespace cupola {

ProjectorWarp load_channel_warp(const ChannelCalibration& calibration);

}  // namespace cupola

#pragma once
// How the master follows the viewer's head (room.tracking in the cluster config): where the poses
// come from, how they are filtered, and when a silent tracker is given up.
#include <cstdint>
#include <string>
#include <vector>

#include "tracking/tracker_mounting.hpp"

namespace cupola {

enum class TrackingSource {
    Fixed = 0,   // the head stays at room.eye_m (the presenter may still move it: "head" command)
    Dtrack = 1,  // an A.R.T. DTrack2 UDP ASCII stream (tracking/dtrack_packet.hpp)
};
enum class HeadFilter {
    None = 0,     // the newest sample as it is
    Smooth = 1,   // exponential smoothing with the time constant smoothing_s (less jitter, more lag)
    Predict = 2,  // the newest sample moved on by its velocity to prediction_s past the frame (less lag)
};

struct HeadTrackingConfig {
    TrackingSource source = TrackingSource::Fixed;
    std::string address = "0.0.0.0";  // where the master listens for the tracker
    uint16_t port = 5000;
    int body = 0;  // the DTrack2 6DOF body on the viewer's head (its id, from 0)
    TrackerMounting mounting;
    double fresh_s = 0.1;    // a sample older than this is held, not extrapolated
    double timeout_s = 2.0;  // no sample for this long: back to the default eye
    HeadFilter filter = HeadFilter::None;
    double smoothing_s = 0.05;
    double prediction_s = 0.02;
};

// "fixed", "dtrack" and "none", "smooth", "predict" (in the enums' orders).
const std::vector<std::string>& tracking_source_names();
const std::vector<std::string>& head_filter_names();

}  // namespace cupola

#pragma once
// The master's view of the viewer's head, decided once per frame for the whole cluster: the
// tracker's samples filtered as configured, the presenter's pose when one is set, and the fallback
// when the tracker falls silent (its last pose while it is late, then the default eye once it
// has been silent for the timeout; each loss and recovery is logged and counted).
// Times are monotonic nanoseconds, passed in, so the rules are tested without waiting.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>

#include "tracking/head_pose.hpp"
#include "tracking/head_tracking_config.hpp"

namespace cupola {

struct HeadTrackerCounters {
    uint64_t packets = 0;         // tracker datagrams read
    uint64_t bad_packets = 0;     // of those: refused (not DTrack2 ASCII output; logged)
    uint64_t without_body = 0;    // of those: well formed, but the head's body was not tracked in it
    uint64_t samples = 0;         // poses taken from the tracker
    uint64_t tracked_frames = 0;  // frames with a fresh sample
    uint64_t held_frames = 0;     // frames on the last pose of a late tracker
    uint64_t default_frames = 0;  // frames at the default eye (no tracking, or lost)
    uint64_t control_frames = 0;  // frames on the presenter's pose
    uint64_t losses = 0;          // the tracker went silent past the timeout
    uint64_t recoveries = 0;      // ... and came back
    nlohmann::json to_json() const;
};

// A frame's pose, and the arrival of the tracker sample it is the first frame to use (for the
// latency from the packet to the snapshot).
struct FrameHeadPose {
    HeadPose pose;
    std::optional<uint64_t> new_sample_arrival_ns;
};

class HeadTracker {
public:
    HeadTracker(const HeadTrackingConfig& config, const glm::dvec3& default_eye_m);

    // A pose measured by the tracker (source Tracked), arrived at arrival_ns. Samples older than
    // the newest are dropped.
    void add_sample(const HeadPose& measured, uint64_t arrival_ns);
    // The presenter's pose (source Control) until cleared with nothing.
    void set_control_pose(std::optional<HeadPose> pose);
    // The pose for the frame built at now_ns.
    FrameHeadPose frame_pose(uint64_t now_ns);

    const HeadPose& default_pose() const { return default_; }
    HeadTrackerCounters& counters() { return counters_; }
    const HeadTrackerCounters& counters() const { return counters_; }

private:
    void filter_sample(const HeadPose& measured, uint64_t arrival_ns);
    HeadPose tracked_pose(uint64_t now_ns) const;
    void note_loss(double silent_s);

    HeadTrackingConfig config_;
    HeadPose default_;
    std::optional<HeadPose> control_;
    std::optional<HeadPose> filtered_;  // the filter's state: the newest sample, smoothed
    glm::dvec3 velocity_m_s{0.0};       // Predict: from the last two samples
    uint64_t last_arrival_ns_ = 0;
    bool sample_unused_ = false;
    bool lost_ = false;  // silent past the timeout since the last sample
    HeadTrackerCounters counters_;
};

}  // namespace cupola

#include "tracking/head_tracker.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

namespace cupola {

namespace {
constexpr double kMinVelocityInterval_s = 5e-4;  // samples closer than this give no velocity

double seconds(uint64_t from_ns, uint64_t to_ns) {
    return to_ns > from_ns ? static_cast<double>(to_ns - from_ns) * 1e-9 : 0.0;
}
}  // namespace

nlohmann::json HeadTrackerCounters::to_json() const {
    return {{"packets", packets},
            {"bad_packets", bad_packets},
            {"without_body", without_body},
            {"samples", samples},
            {"tracked_frames", tracked_frames},
            {"held_frames", held_frames},
            {"default_frames", default_frames},
            {"control_frames", control_frames},
            {"losses", losses},
            {"recoveries", recoveries}};
}

HeadTracker::HeadTracker(const HeadTrackingConfig& config, const glm::dvec3& default_eye_m) : config_(config) {
    default_.position_m = default_eye_m;
}

void HeadTracker::add_sample(const HeadPose& measured, uint64_t arrival_ns) {
    if (filtered_ && arrival_ns < last_arrival_ns_) return;
    if (lost_) {
        lost_ = false;
        ++counters_.recoveries;
        filtered_.reset();  // the filter starts again from this sample
        spdlog::info("master: the head tracker is back");
    }
    filter_sample(measured, arrival_ns);
    last_arrival_ns_ = arrival_ns;
    sample_unused_ = true;
    ++counters_.samples;
}

void HeadTracker::filter_sample(const HeadPose& measured, uint64_t arrival_ns) {
    HeadPose next = measured;
    next.source = HeadSource::Tracked;
    const double dt = filtered_ ? seconds(last_arrival_ns_, arrival_ns) : 0.0;
    if (config_.filter == HeadFilter::Smooth && filtered_) {
        const double a = 1.0 - std::exp(-dt / std::max(config_.smoothing_s, 1e-6));
        next.position_m = glm::mix(filtered_->position_m, measured.position_m, a);
        next.orientation = glm::slerp(filtered_->orientation, measured.orientation, a);
    }
    if (config_.filter == HeadFilter::Predict)
        velocity_m_s = filtered_ && dt > kMinVelocityInterval_s ? (measured.position_m - filtered_->position_m) / dt
                                                                : glm::dvec3(0.0);
    filtered_ = next;
}

void HeadTracker::set_control_pose(std::optional<HeadPose> pose) {
    control_ = pose;
    if (control_) control_->source = HeadSource::Control;
}

// The newest sample, carried to the frame's time (and prediction_s beyond) by its velocity.
HeadPose HeadTracker::tracked_pose(uint64_t now_ns) const {
    HeadPose p = *filtered_;
    if (config_.filter == HeadFilter::Predict)
        p.position_m += velocity_m_s * (seconds(last_arrival_ns_, now_ns) + config_.prediction_s);
    return p;
}

void HeadTracker::note_loss(double silent_s) {
    lost_ = true;
    ++counters_.losses;
    spdlog::warn("master: no head tracker sample for {:.2f} s: back to the default eye", silent_s);
}

FrameHeadPose HeadTracker::frame_pose(uint64_t now_ns) {
    FrameHeadPose out;
    if (control_) {
        ++counters_.control_frames;
        out.pose = *control_;
        return out;
    }
    const double age_s = filtered_ ? seconds(last_arrival_ns_, now_ns) : 0.0;
    if (filtered_ && !lost_ && age_s > config_.timeout_s) note_loss(age_s);
    if (!filtered_ || lost_) {
        ++counters_.default_frames;
        out.pose = default_;
        return out;
    }
    if (age_s > config_.fresh_s) {
        ++counters_.held_frames;
        out.pose = *filtered_;
        out.pose.source = HeadSource::Held;
        return out;
    }
    ++counters_.tracked_frames;
    out.pose = tracked_pose(now_ns);
    if (sample_unused_) out.new_sample_arrival_ns = last_arrival_ns_;
    sample_unused_ = false;
    return out;
}

}  // namespace cupola

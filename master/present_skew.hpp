#pragma once
// The swap lock's measurement (docs/SWAP_LOCK.md): each channel's report of frame N+1 carries
// when it showed frame N (CLOCK_MONOTONIC ns, just after the swap; one clock on one host, and
// comparable across hosts only as far as their clocks agree). Per frame shown by two or more
// channels: the present skew (latest minus earliest present), the release (earliest present minus
// the latest "ready", what the lock's round trip costs) and each channel's wait (its present minus
// its own ready). Kept for the last kMaxSamples frames; --stats gives median, p99 and max.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "wire/reports.hpp"

namespace cupola {

struct FramePresentation {
    uint64_t frame = 0;
    int channels = 0;               // channels that reported showing it
    double skew_ms = 0.0;           // latest present - earliest present
    double release_ms = 0.0;        // earliest present - latest ready (channels with both; may be < 0 unlocked)
    std::map<int, double> wait_ms;  // per channel: present - its ready

    nlohmann::json to_json() const;
};

class PresentSkew {
public:
    static constexpr size_t kMaxSamples = 100000;

    // A frame's reports (`current`) and the previous frame's (`previous`, for the ready times of
    // the frame they show): the presentation of the frame they name, when two or more channels
    // report showing the same frame. Reports without a presentation block are left out.
    std::optional<FramePresentation> add(const std::map<int, FrameReport>& current,
                                         const std::map<int, FrameReport>& previous);

    size_t frames() const { return skew_ms_.size(); }
    // {frames, skew_ms {median, p99, max}, release_ms {...}, wait_ms {channel: {...}}}.
    nlohmann::json to_json() const;

private:
    std::deque<double> skew_ms_, release_ms_;
    std::map<int, std::deque<double>> wait_ms_;
};

// {median, p99, max} of the samples (nearest rank); null when there are none.
nlohmann::json percentile_summary(const std::deque<double>& samples);

}  // namespace cupola

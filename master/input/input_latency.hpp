#pragma once
// Latency from a navigation device's report to the snapshot that carries its effect leaving the
// master: collected per frame that used fresh input, summarised as median / p99 / max.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace cupola {

class InputLatency {
public:
    // Returns the latency in milliseconds and keeps it.
    double add(uint64_t report_ns, uint64_t sent_ns) {
        const double ms = sent_ns > report_ns ? static_cast<double>(sent_ns - report_ns) / 1e6 : 0.0;
        if (samples_.size() < kMaxSamples) samples_.push_back(ms);  // a long show keeps the first million
        return ms;
    }
    size_t count() const { return samples_.size(); }
    double percentile(double p) const {
        if (samples_.empty()) return 0.0;
        std::vector<double> s = samples_;
        std::sort(s.begin(), s.end());
        const size_t i =
            std::min(s.size() - 1, static_cast<size_t>(p / 100.0 * static_cast<double>(s.size() - 1) + 0.5));
        return s[i];
    }
    std::string summary() const {
        return fmt::format("{} frames, median {:.2f} ms, p99 {:.2f} ms, max {:.2f} ms", count(), percentile(50),
                           percentile(99), percentile(100));
    }

private:
    static constexpr size_t kMaxSamples = 1000000;
    std::vector<double> samples_;
};

}  // namespace cupola

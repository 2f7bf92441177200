#include "present_skew.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace cupola {

namespace {

void keep(std::deque<double>& d, double v) {
    d.push_back(v);
    if (d.size() > PresentSkew::kMaxSamples) d.pop_front();
}

double ns_to_ms(int64_t ns) { return static_cast<double>(ns) / 1e6; }

// The frame most reports say they showed (normally the previous one).
std::optional<uint64_t> shown_frame(const std::map<int, FrameReport>& current) {
    std::map<uint64_t, int> votes;
    for (const auto& [id, rep] : current)
        if (rep.presentation && rep.presentation->has_present) ++votes[rep.presentation->presented_frame];
    std::optional<uint64_t> best;
    int most = 0;
    for (const auto& [frame, n] : votes)
        if (n > most) most = n, best = frame;
    return best;
}

}  // namespace

nlohmann::json FramePresentation::to_json() const {
    nlohmann::json waits = nlohmann::json::object();
    for (const auto& [id, w] : wait_ms) waits[std::to_string(id)] = w;
    return {
        {"frame", frame}, {"channels", channels}, {"skew_ms", skew_ms}, {"release_ms", release_ms}, {"wait_ms", waits}};
}

std::optional<FramePresentation> PresentSkew::add(const std::map<int, FrameReport>& current,
                                                  const std::map<int, FrameReport>& previous) {
    const std::optional<uint64_t> frame = shown_frame(current);
    if (!frame) return std::nullopt;
    FramePresentation fp;
    fp.frame = *frame;
    uint64_t first = std::numeric_limits<uint64_t>::max(), last = 0, last_ready = 0;
    for (const auto& [id, rep] : current) {
        const auto& t = rep.presentation;
        if (!t || !t->has_present || t->presented_frame != *frame) continue;
        ++fp.channels;
        first = std::min(first, t->present_ns);
        last = std::max(last, t->present_ns);
        auto prev = previous.find(id);
        if (prev == previous.end() || prev->second.frame != *frame || !prev->second.presentation) continue;
        const uint64_t ready = prev->second.presentation->ready_ns;
        if (ready == 0) continue;
        last_ready = std::max(last_ready, ready);
        fp.wait_ms[id] = ns_to_ms(static_cast<int64_t>(t->present_ns - ready));
    }
    if (fp.channels < 2) return std::nullopt;
    fp.skew_ms = ns_to_ms(static_cast<int64_t>(last - first));
    fp.release_ms = last_ready ? ns_to_ms(static_cast<int64_t>(first - last_ready)) : 0.0;
    keep(skew_ms_, fp.skew_ms);
    if (last_ready) keep(release_ms_, fp.release_ms);
    for (const auto& [id, w] : fp.wait_ms) keep(wait_ms_[id], w);
    return fp;
}

nlohmann::json percentile_summary(const std::deque<double>& samples) {
    if (samples.empty()) return nullptr;
    std::vector<double> v(samples.begin(), samples.end());
    std::sort(v.begin(), v.end());
    auto rank = [&](double p) {
        const size_t k = static_cast<size_t>(std::ceil(p * static_cast<double>(v.size())));
        return v[std::clamp<size_t>(k, 1, v.size()) - 1];
    };
    return {{"median", rank(0.5)}, {"p99", rank(0.99)}, {"max", v.back()}};
}

nlohmann::json PresentSkew::to_json() const {
    nlohmann::json waits = nlohmann::json::object();
    for (const auto& [id, d] : wait_ms_) waits[std::to_string(id)] = percentile_summary(d);
    return {{"frames", skew_ms_.size()},
            {"skew_ms", percentile_summary(skew_ms_)},
            {"release_ms", percentile_summary(release_ms_)},
            {"wait_ms", waits}};
}

}  // namespace cupola

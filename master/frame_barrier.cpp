#include "frame_barrier.hpp"

#include <algorithm>

namespace cupola {

FrameBarrier::FrameBarrier(const std::vector<int>& ids, std::chrono::milliseconds timeout,
                           std::chrono::milliseconds first_timeout)
    : timeout_(timeout), first_timeout_(std::max(timeout, first_timeout)) {
    for (int id : ids) channels_[id] = Entry{};
}

bool FrameBarrier::on_alive(int channel, Clock::time_point now) {
    auto it = channels_.find(channel);
    if (it == channels_.end()) return false;
    Entry& e = it->second;
    if (e.state == ChannelState::Live) return false;
    e.state = ChannelState::Live;
    e.reported = false;
    e.expected_since = now;
    return true;
}

void FrameBarrier::on_restart(int channel, Clock::time_point now) {
    auto it = channels_.find(channel);
    if (it == channels_.end()) return;
    it->second.state = ChannelState::Live;
    it->second.reported = false;
    it->second.ever_reported = false;  // a new process: its first frame compiles its shaders again
    it->second.expected_since = now;
}

void FrameBarrier::start_frame(uint64_t frame, Clock::time_point now) {
    frame_ = frame;
    for (auto& [id, e] : channels_) {
        e.reported = false;
        e.expected_since = now;
    }
}

bool FrameBarrier::on_report(int channel, uint64_t frame, Clock::time_point now) {
    auto it = channels_.find(channel);
    if (it == channels_.end() || frame != frame_) return false;
    on_alive(channel, now);
    it->second.reported = true;
    it->second.ever_reported = true;
    return true;
}

std::vector<int> FrameBarrier::pending() const {
    std::vector<int> out;
    for (const auto& [id, e] : channels_)
        if (e.state == ChannelState::Live && !e.reported) out.push_back(id);
    return out;
}

std::vector<int> FrameBarrier::expire(Clock::time_point now) {
    std::vector<int> out;
    for (auto& [id, e] : channels_) {
        if (e.state == ChannelState::Live && !e.reported && now >= deadline(e)) {
            e.state = ChannelState::Dropped;
            out.push_back(id);
        }
    }
    return out;
}

FrameBarrier::Clock::time_point FrameBarrier::next_deadline() const {
    auto best = Clock::time_point::max();
    for (const auto& [id, e] : channels_)
        if (e.state == ChannelState::Live && !e.reported && deadline(e) < best) best = deadline(e);
    return best;
}

ChannelState FrameBarrier::state(int channel) const {
    auto it = channels_.find(channel);
    return it == channels_.end() ? ChannelState::Absent : it->second.state;
}

int FrameBarrier::live_count() const {
    int n = 0;
    for (const auto& [id, e] : channels_) n += e.state == ChannelState::Live;
    return n;
}

}  // namespace cupola

#pragma once
// The frame barrier's bookkeeping, free of sockets so it can be tested on its own.
// Frame N+1 may start when every live channel has reported frame N. A live channel that stays
// silent for `timeout` after a frame started is dropped so the rest go on; any authentic message
// from a dropped (or never seen) channel makes it live again and it is expected for the
// current frame. Until a channel's first report since it was first seen or its process
// restarted, `first_timeout` applies instead (at least `timeout`): a node's first frame compiles
// its shaders, which on a software renderer under load takes longer than a steady frame.
#include <chrono>
#include <cstdint>
#include <map>
#include <vector>

namespace cupola {

enum class ChannelState { Absent, Live, Dropped };

class FrameBarrier {
public:
    using Clock = std::chrono::steady_clock;

    FrameBarrier(const std::vector<int>& channel_ids, std::chrono::milliseconds timeout,
                 std::chrono::milliseconds first_timeout = std::chrono::milliseconds(0));

    // Returns true when the channel was absent or dropped and is now live again.
    bool on_alive(int channel, Clock::time_point now);
    // A new process took over the channel (it may still be live under the old one): it is live
    // and expected for the current frame from now.
    void on_restart(int channel, Clock::time_point now);
    void start_frame(uint64_t frame, Clock::time_point now);
    // Returns false when the report is for another frame or an unknown channel.
    bool on_report(int channel, uint64_t frame, Clock::time_point now);

    // Live channels that have not reported the current frame.
    std::vector<int> pending() const;
    bool complete() const { return pending().empty(); }
    // Drops live channels silent past the timeout for the current frame; returns them.
    std::vector<int> expire(Clock::time_point now);
    // When the next timeout would fire (Clock::time_point::max() when nothing is pending).
    Clock::time_point next_deadline() const;

    ChannelState state(int channel) const;
    int live_count() const;
    uint64_t frame() const { return frame_; }
    bool known(int channel) const { return channels_.count(channel) != 0; }

private:
    struct Entry {
        ChannelState state = ChannelState::Absent;
        bool reported = false;
        bool ever_reported = false;  // since the channel was first seen or its process restarted
        Clock::time_point expected_since{};
    };
    // When a live channel that has not reported is dropped.
    Clock::time_point deadline(const Entry& e) const {
        return e.expected_since + (e.ever_reported ? timeout_ : first_timeout_);
    }
    std::map<int, Entry> channels_;
    std::chrono::milliseconds timeout_, first_timeout_;
    uint64_t frame_ = 0;
};

}  // namespace cupola

#pragma once
// The master's side of the wire protocol as a state machine: no sockets, no threads, no clock
// (every step is given the time). The node (master/master_node.cpp) feeds it what the endpoint
// received and sends what it returns; tests and the fuzz target drive it the same way.
//
//   joining   a hello to session 0 (or to an older master's) is answered with a welcome, at most
//             every 20 ms per channel; a hello to our session completes the handshake: the channel
//             is live (a hello from a new process of a live channel replaces it);
//   frame     the snapshot goes out, and again every resend interval while the barrier
//             (frame_barrier.hpp) waits; a channel silent for the channel timeout is dropped, one
//             that (re)joins is sent the snapshot at once; reports are kept for the frame;
//   present   with the swap lock (docs/SWAP_LOCK.md): as soon as the barrier is complete (every
//             live channel reported "ready N", or the rest were dropped) the present N goes out,
//             and again every resend interval until the next frame starts (its snapshot, or the
//             quit, implies the present at the slaves);
//   between   after the barrier: reports and joins still count, a joined channel gets the snapshot;
//   quitting  a quit every 50 ms until every live channel acknowledged, for at most 2 s.
#include <chrono>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <vector>

#include "frame_barrier.hpp"
#include "master_counters.hpp"
#include "net/wire_endpoint.hpp"
#include "session/session_send.hpp"
#include "wire/reports.hpp"

namespace cupola {

// A datagram for every snapshot destination (common/session/session_send.hpp).
using MasterSend = SessionSend;

struct MasterActions {
    std::vector<MasterSend> sends;
    std::vector<nlohmann::json> events;  // lines for the events file (channel_joined, channel_dropped)
    std::vector<int> joined;             // channels that became live
    std::vector<int> dropped;            // live channels that timed out
};

struct MasterTimings {
    std::chrono::milliseconds resend_interval{100};
    std::chrono::milliseconds channel_timeout{2000};
    bool swap_lock = false;  // send a present once the barrier is complete (network.swap_lock)
    // Before a channel's first report since it joined or restarted; never less than
    // channel_timeout (0: the same). network.first_frame_timeout_ms.
    std::chrono::milliseconds first_frame_timeout{0};
};

enum class MasterPhase { Joining, Frame, Between, Quitting, Done };

class MasterSession {
public:
    using Clock = std::chrono::steady_clock;

    static constexpr std::chrono::milliseconds kWelcomeInterval{20};  // per channel, at most one welcome
    static constexpr std::chrono::milliseconds kQuitRound{50};
    static constexpr std::chrono::milliseconds kQuitLimit{2000};

    // session: this master's nonce (hellos addressed to it complete the handshake).
    MasterSession(const std::vector<int>& channel_ids, uint64_t session, MasterTimings timings);

    MasterActions on_message(const ReceivedMessage& rm, Clock::time_point now);
    // Broadcasts frame `frame` (its encoded snapshot); sent_ns: CLOCK_MONOTONIC as it goes out,
    // subtracted from the reports' arrival times (one-host latency).
    MasterActions start_frame(uint64_t frame, std::vector<uint8_t> payload, Clock::time_point now, uint64_t sent_ns);
    // The barrier is done with the frame: its reports; later ones are not kept.
    std::map<int, FrameReport> end_frame();
    // Tells the slaves to quit; `frame`: the frame the master is at (the quit names the next).
    MasterActions start_quit(uint64_t frame, Clock::time_point now);
    // The time-driven rules: drops and resends in a frame, quit rounds.
    MasterActions tick(Clock::time_point now);
    // When tick() next has something to do (Clock::time_point::max(): nothing).
    Clock::time_point next_wake() const;
    // The present of the current frame went out (swap lock).
    bool presented() const { return presented_; }

    MasterPhase phase() const { return phase_; }
    bool all_live() const { return barrier_.live_count() == static_cast<int>(ids_.size()); }
    bool frame_complete() const { return barrier_.complete(); }
    bool quit_done() const { return phase_ == MasterPhase::Done; }
    // Live channels that did not acknowledge the quit.
    std::vector<int> unconfirmed_quits() const;
    // The last frame every live channel rendered, by their hellos (none if one has not rendered).
    std::optional<uint64_t> resume_after() const;
    const FrameBarrier& barrier() const { return barrier_; }
    MasterCounters& counters() { return counters_; }
    const MasterCounters& counters() const { return counters_; }
    uint64_t frame() const { return frame_; }

private:
    void hello(const ReceivedMessage& rm, Clock::time_point now, MasterActions& out);
    void welcome(const Message& m, const HelloMessage& h, Clock::time_point now, MasterActions& out);
    void report(const Message& m, Clock::time_point now, MasterActions& out);
    void verified(const ReceivedMessage& rm, Clock::time_point now, MasterActions& out);
    void joined(int channel, MasterActions& out);
    void resend(Clock::time_point now, MasterActions& out);
    void quit_round(Clock::time_point now, MasterActions& out);
    void maybe_present(Clock::time_point now, MasterActions& out);
    void send_present(Clock::time_point now, MasterActions& out);

    std::vector<int> ids_;
    uint64_t session_;
    MasterTimings timings_;
    FrameBarrier barrier_;
    MasterCounters counters_;
    MasterPhase phase_ = MasterPhase::Joining;
    uint64_t frame_ = 0;
    std::vector<uint8_t> payload_;  // the current frame's snapshot
    uint64_t sent_ns_ = 0;          // while in a frame
    Clock::time_point last_send_{};
    bool presented_ = false;  // the current frame's present went out (swap lock)
    Clock::time_point last_present_{};
    std::map<int, FrameReport> reports_;
    std::map<int, Clock::time_point> last_welcome_;
    std::map<int, HelloMessage> hellos_;  // the last verified hello of each channel's process
    std::set<int> quit_acked_;
    Clock::time_point quit_until_{}, round_end_{};
};

}  // namespace cupola

#pragma once
// A slave's side of the wire protocol as a state machine: no sockets, no EGL, no threads, no clock
// (every step is given the time). The node (slave/slave_node.cpp) feeds it what the endpoint
// received and carries out what it returns; tests and the fuzz target drive it the same way.
//
//   joining    hello to session 0 every 100 ms until a master welcomes us (wire/session_guard.hpp),
//              then hello to the master's session, which completes the handshake;
//   rendering  each snapshot is rendered once and reported; a resent snapshot (our report was
//              lost) repeats the report; older ones are ignored; after a stall only the newest
//              queued snapshot is rendered. Without snapshots for 500 ms a hello says we are here,
//              after 1 s addressed to session 0 (a restarted master knows no channel);
//   showing    with the swap lock (docs/SWAP_LOCK.md) a rendered frame is held after its report
//              ("ready N") until the master's present N; a later present, a snapshot to render
//              or a quit implies it (a lost present costs no frame); late and repeated presents
//              are ignored. Without the swap lock a frame is shown as soon as it is reported;
//   quitting   the master's quit is acknowledged, and again for every quit for 300 ms.
// Without any snapshot for the idle timeout the slave gives up (exit code 3).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "net/wire_endpoint.hpp"
#include "session/slave_counters.hpp"
#include "session/session_send.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

struct SlaveSessionConfig {
    int channel = 0;
    uint32_t process_id = 0;                                       // named in our hellos (the master's log)
    std::chrono::seconds idle_timeout{30};                         // no snapshot for this long: exit 3
    size_t scene_body_count = std::numeric_limits<size_t>::max();  // body ids beyond: malformed
    std::string scene_file;                                        // named when a snapshot does not fit the scene
    std::string log_name = "slave";                                // "slave <channel name>"
    bool swap_lock = true;                                         // hold each frame until its present
};

// A datagram for the master's report address (common/session/session_send.hpp).
using SlaveSend = SessionSend;

// Render this snapshot, then hand the report to SlaveSession::rendered().
struct RenderJob {
    Snapshot snapshot;
    std::string hash;  // snapshot_hash of its payload
};

// Why a held frame is shown now.
enum class PresentCause : uint8_t {
    Present,   // the master's present for it
    Implied,   // a later present, the next snapshot to render, or the quit
    Unlocked,  // no swap lock: at once after its report
};
const char* present_cause_name(PresentCause c);

// Show this frame (the output's present), then hand its time to SlaveSession::presented().
struct PresentJob {
    uint64_t frame = 0;
    uint64_t ready_ns = 0;  // CLOCK_MONOTONIC when it was ready (its report's)
    PresentCause cause = PresentCause::Present;
};

// The node carries these out in this order: sends, present, render.
struct SlaveActions {
    std::vector<SlaveSend> sends;
    std::optional<PresentJob> present;
    std::optional<RenderJob> render;
    std::optional<int> exit_code;  // leave now: 0 after the quit linger, 3 idle
};

class SlaveSession {
public:
    using Clock = std::chrono::steady_clock;

    static constexpr std::chrono::milliseconds kJoinHelloInterval{100};
    static constexpr std::chrono::milliseconds kQuietHelloInterval{500};  // also: quiet after this long
    static constexpr std::chrono::milliseconds kSilentAfter{1000};        // hellos go to session 0
    static constexpr std::chrono::milliseconds kQuitLinger{300};

    SlaveSession(SlaveSessionConfig config, Clock::time_point start);

    // Queues a received message; step() handles the queue in order.
    void receive(ReceivedMessage rm);
    bool has_queued() const { return !inbox_.empty(); }
    // Handles the oldest queued message. A snapshot that has newer ones of the same master session
    // queued behind it gives way to the newest (catching up after a stall).
    SlaveActions step(Clock::time_point now);
    // The time-driven rules: hellos, the idle exit, the end of the quit linger.
    SlaveActions tick(Clock::time_point now);
    // When tick() next has something to do at the latest (the node receives until then).
    Clock::time_point next_wake(Clock::time_point now) const;
    // The last RenderJob was rendered: `rep` carries render_ms, write_ms, snapshot_received_ns,
    // glare and presentation->ready_ns; the session fills in the rest (wire_rejected: the
    // endpoint's rejected datagrams; the last present's frame and time) and sends it. Without the
    // swap lock the frame is to be shown at once; with it, it is held.
    SlaveActions rendered(FrameReport rep, uint64_t wire_rejected);
    // The last PresentJob's frame was shown at present_ns (CLOCK_MONOTONIC, just after the swap):
    // the next report carries it.
    void presented(uint64_t frame, uint64_t present_ns);
    // The frame rendered, reported and not shown yet (swap lock).
    std::optional<uint64_t> held_frame() const;

    const SlaveCounters& counters() const { return counters_; }
    uint64_t master_session() const { return master_session_; }
    std::optional<uint64_t> last_frame() const { return last_frame_; }
    bool quitting() const { return linger_until_.has_value(); }

private:
    void handle(ReceivedMessage rm, Clock::time_point now, SlaveActions& out);
    void opened(const ReceivedMessage& rm, Clock::time_point now, SlaveActions& out);
    void linger(const ReceivedMessage& rm, SlaveActions& out);
    void snapshot(const ReceivedMessage& rm, Clock::time_point now, SlaveActions& out);
    bool repeat_or_ignore(const Message& sm, const std::string& hash, SlaveActions& out);
    std::optional<Snapshot> decode(const Message& sm);
    void catch_up(ReceivedMessage& current);
    void send_hello(uint64_t to, Clock::time_point now, SlaveActions& out);
    void send_quit_ack(SlaveActions& out);
    void present(const Message& m, SlaveActions& out);
    void release(PresentCause cause, SlaveActions& out);

    SlaveSessionConfig config_;
    SlaveCounters counters_;
    HelloMessage hello_;
    uint64_t master_session_ = 0;
    std::optional<uint64_t> last_frame_;
    std::optional<FrameReport> last_report_;
    struct Job {
        uint64_t frame = 0;
        std::string hash;
    };
    std::optional<Job> job_;                     // handed out, not reported yet
    std::optional<PresentJob> held_;             // reported, waiting for its present (swap lock)
    std::optional<PresentTiming> last_present_;  // for the next report
    bool fresh_session_ = false;                 // a master session was just established: any frame may come next
    bool need_welcome_ = false;                  // authentic packets from a master session we do not know: it restarted
    bool rendered_in_session_ = false;           // a frame was rendered (or its report repeated) for this master
    Clock::time_point last_snapshot_;
    std::optional<Clock::time_point> last_hello_;
    std::deque<ReceivedMessage> inbox_;
    std::optional<Clock::time_point> linger_until_;  // quitting: acknowledge quits until then
    uint64_t quit_frame_ = 0;
    bool exited_ = false;
};

}  // namespace cupola

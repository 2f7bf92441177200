#pragma once
// Control message bodies: slave -> master (hello, quit-ack, frame reports) and the
// master's welcome.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cupola {

// Hello and QuitAck carry this.
struct HelloMessage {
    uint16_t channel = 0;
    uint32_t process_id = 0;  // for the operator's log
    bool has_frame = false;   // this process has rendered a frame...
    uint64_t last_frame = 0;  // ...and this was the last (a restarted master resumes after it)
};

// master -> one slave process (addressed by to_session in the header).
struct WelcomeMessage {
    uint16_t channel = 0;
    uint64_t frame = 0;  // the frame the master is at
};

// One channel's occlusion-query result for one glare source: the solid angle (steradian) of the
// source's disc in the directions this channel owns (each direction of the dome is owned by
// exactly one channel, so sums over channels count nothing twice), in total and unoccluded, per
// angular wedge around the source's centre in the cluster-wide glare frame (for the direction
// toward the visible part).
struct GlareMeasurement {
    static constexpr int kWedges = 8;
    uint16_t body = 0xFFFF;  // as GlareSource: body id or catalogue star
    uint32_t star = 0;
    uint64_t frame = 0;  // the frame whose render the queries ran in
    float total_sr = 0.0f;
    float visible_sr[kWedges] = {};
    float visible_total_sr() const {
        float s = 0.0f;
        for (float v : visible_sr) s += v;
        return s;
    }
};

// master -> slaves (swap lock): every live channel is ready for `frame`, or the rest timed out;
// show it. The header's frame must be the same.
struct PresentMessage {
    uint64_t frame = 0;
};

// A report's presentation block (docs/SWAP_LOCK.md): when this frame was ready to show, and when
// the channel last showed a frame (normally the previous one), both CLOCK_MONOTONIC ns.
struct PresentTiming {
    uint64_t ready_ns = 0;         // this report's frame rendered (and warped): ready to show
    bool has_present = false;      // a frame was shown since the channel started...
    uint64_t presented_frame = 0;  // ...this one,
    uint64_t present_ns = 0;       // just after its swap
    bool operator==(const PresentTiming&) const = default;
};

// "frame N rendered" (with the swap lock: "ready N") with per-channel measurements.
struct FrameReport {
    uint16_t channel = 0;
    uint64_t frame = 0;
    std::string snapshot_hash;  // 16 hex digits
    float render_ms = 0.0f;
    float write_ms = 0.0f;
    uint64_t packets_rejected = 0;  // this slave's totals so far
    uint64_t snapshots_missed = 0;
    uint64_t snapshot_received_ns = 0;    // CLOCK_MONOTONIC when the whole snapshot arrived (one-host latency)
    std::vector<GlareMeasurement> glare;  // this frame's (or, if the GPU was late, an earlier frame's) queries
    // Appended after the glare block when present; a report without it (an older slave) still
    // decodes, so the protocol version stays 2.
    std::optional<PresentTiming> presentation;
};

std::vector<uint8_t> encode_hello(const HelloMessage& m);
HelloMessage decode_hello(const std::vector<uint8_t>& payload);
std::vector<uint8_t> encode_welcome(const WelcomeMessage& m);
WelcomeMessage decode_welcome(const std::vector<uint8_t>& payload);
std::vector<uint8_t> encode_frame_report(const FrameReport& r);
FrameReport decode_frame_report(const std::vector<uint8_t>& payload);
std::vector<uint8_t> encode_present(const PresentMessage& m);
PresentMessage decode_present(const std::vector<uint8_t>& payload);

}  // namespace cupola

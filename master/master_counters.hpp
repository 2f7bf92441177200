#pragma once
// What the master counts besides the wire's own counters (net/wire_endpoint.hpp): the protocol
// events an operator looks for when a channel misbehaves.
#include <cstdint>
#include <nlohmann/json.hpp>

namespace cupola {

struct MasterCounters {
    uint64_t frames = 0;
    uint64_t snapshots_sent = 0;
    uint64_t snapshot_resends = 0;    // the barrier waited past resend_interval_ms, or a channel (re)joined
    uint64_t welcomes_sent = 0;       // answers to hellos from processes that do not know this session
    uint64_t late_reports = 0;        // reports for a frame other than the current one
    uint64_t channel_drops = 0;       // a live channel timed out
    uint64_t channel_joins = 0;       // a channel became live (first time, after a drop, or a new process)
    uint64_t channel_restarts = 0;    // of those: a new process replaced a live one
    uint64_t malformed_messages = 0;  // authentic, but the body did not decode
    uint64_t unknown_channel = 0;     // authentic, from a channel id not in the config
    uint64_t quit_acks = 0;
    uint64_t presents_sent = 0;     // swap lock: one per frame, once the barrier is complete
    uint64_t present_resends = 0;   // the same present again every resend interval until the next frame
    uint64_t control_commands = 0;  // lines from the control channel
    uint64_t control_errors = 0;    // of those: refused (named in the reply)

    nlohmann::json to_json() const {
        return {{"frames", frames},
                {"snapshots_sent", snapshots_sent},
                {"snapshot_resends", snapshot_resends},
                {"welcomes_sent", welcomes_sent},
                {"late_reports", late_reports},
                {"channel_drops", channel_drops},
                {"channel_joins", channel_joins},
                {"channel_restarts", channel_restarts},
                {"malformed_messages", malformed_messages},
                {"unknown_channel", unknown_channel},
                {"quit_acks", quit_acks},
                {"presents_sent", presents_sent},
                {"present_resends", present_resends},
                {"control_commands", control_commands},
                {"control_errors", control_errors}};
    }
};

}  // namespace cupola

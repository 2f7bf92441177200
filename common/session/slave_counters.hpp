#pragma once
// What a slave counts besides the wire's own counters (net/wire_endpoint.hpp); SlaveSession keeps them.
#include <cstdint>
#include <nlohmann/json.hpp>

namespace cupola {

struct SlaveCounters {
    uint64_t frames_rendered = 0;
    uint64_t resent_snapshots = 0;     // the current frame's snapshot again: our report was lost, repeated
    uint64_t late_snapshots = 0;       // older than the frame already rendered (reordered or a stale resend)
    uint64_t skipped_snapshots = 0;    // a newer one was already queued behind it (catching up after a stall)
    uint64_t missed_frames = 0;        // frame numbers that never arrived (we were dropped meanwhile)
    uint64_t malformed_snapshots = 0;  // authentic, but the body did not decode or does not fit the scene
    uint64_t rerendered = 0;           // a restarted master sent a frame we had, with other content
    uint64_t hellos_sent = 0;
    uint64_t master_sessions = 0;   // master sessions established (1 + master restarts)
    uint64_t frames_presented = 0;  // frames shown (the output's present)
    uint64_t presents_implied = 0;  // of those: shown on a later present, snapshot or quit (a present was lost)
    uint64_t stale_presents = 0;    // presents for a frame already shown or not held (late, repeated, malformed)

    nlohmann::json to_json() const {
        return {{"frames_rendered", frames_rendered},
                {"resent_snapshots", resent_snapshots},
                {"late_snapshots", late_snapshots},
                {"skipped_snapshots", skipped_snapshots},
                {"missed_frames", missed_frames},
                {"malformed_snapshots", malformed_snapshots},
                {"rerendered", rerendered},
                {"hellos_sent", hellos_sent},
                {"master_sessions", master_sessions},
                {"frames_presented", frames_presented},
                {"presents_implied", presents_implied},
                {"stale_presents", stale_presents}};
    }
};

}  // namespace cupola

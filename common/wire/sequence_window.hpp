#pragma once
// Replay protection for one sender session: remembers which of the last kSize sequence numbers
// arrived and when. A datagram never seen is fresh (or reordered, when a later one came first); a
// repeat soon after the first copy is a network duplicate; a repeat long after it, or anything
// older than the window, is a replay. Each is dropped except fresh and reordered ones.
#include <array>
#include <bitset>
#include <cstdint>

namespace cupola {

class SequenceWindow {
public:
    static constexpr uint32_t kSize = 1024;
    enum class Verdict { Fresh, Reordered, Duplicate, Replayed };

    // A repeat within `duplicate_horizon_ns` of the first copy counts as a duplicate, later as a replay.
    explicit SequenceWindow(uint64_t duplicate_horizon_ns = 500'000'000ull) : horizon_ns_(duplicate_horizon_ns) {}

    // Classifies `sequence` arriving at `now_ns` (a monotonic clock) and remembers it when accepted.
    Verdict check(uint32_t sequence, uint64_t now_ns);

    uint32_t highest() const { return highest_; }

private:
    void mark(uint32_t sequence, uint64_t now_ns);

    uint64_t horizon_ns_;
    bool started_ = false;
    uint32_t highest_ = 0;
    std::bitset<kSize> seen_;
    std::array<uint64_t, kSize> seen_at_{};
};

const char* sequence_verdict_name(SequenceWindow::Verdict v);

}  // namespace cupola

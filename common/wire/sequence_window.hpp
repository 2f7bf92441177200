#pragma once
// Replay protection for one sender session: remembers which of the last kSize sequence numbers
// arrived, when, and how many of the sender's datagrams came before each. A datagram never seen
// is fresh (or reordered, when a later one came first). A repeat is a network duplicate when it
// comes soon after the first copy, in time or in arrival order: a copy the network made follows
// its original within milliseconds, so few datagrams come between them however late the receiver
// reads them, and its arrival time may even read earlier than the first copy's (one stamped by
// the kernel, the other at the read). A repeat both long after the first copy and after many
// other datagrams, or anything older than the window, is a replay. Each is dropped except fresh
// and reordered ones; duplicate and replay differ only in what is counted.
#include <array>
#include <bitset>
#include <cstdint>

namespace cupola {

class SequenceWindow {
public:
    static constexpr uint32_t kSize = 1024;
    // A repeat with fewer of the sender's datagrams than this between it and the first copy is a
    // duplicate whatever the clock says (the sender's burst in the network's few milliseconds).
    static constexpr uint64_t kDuplicateArrivals = 16;
    enum class Verdict { Fresh, Reordered, Duplicate, Replayed };

    // A repeat within `duplicate_horizon_ns` of the first copy counts as a duplicate; later, as a
    // replay unless it is also within kDuplicateArrivals of it.
    explicit SequenceWindow(uint64_t duplicate_horizon_ns = 500'000'000ull) : horizon_ns_(duplicate_horizon_ns) {}

    // Classifies `sequence` arriving at `now_ns` (a monotonic clock) and remembers it when accepted.
    Verdict check(uint32_t sequence, uint64_t now_ns);

    uint32_t highest() const { return highest_; }

private:
    void mark(uint32_t sequence, uint64_t now_ns);
    Verdict repeat(uint32_t slot, uint64_t now_ns) const;

    uint64_t horizon_ns_;
    bool started_ = false;
    uint32_t highest_ = 0;
    std::bitset<kSize> seen_;
    uint64_t arrivals_ = 0;  // datagrams checked so far
    std::array<uint64_t, kSize> seen_at_{};
    std::array<uint64_t, kSize> seen_arrival_{};
};

const char* sequence_verdict_name(SequenceWindow::Verdict v);

}  // namespace cupola

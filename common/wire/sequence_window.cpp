#include "wire/sequence_window.hpp"

namespace cupola {

void SequenceWindow::mark(uint32_t sequence, uint64_t now_ns) {
    seen_.set(sequence % kSize);
    seen_at_[sequence % kSize] = now_ns;
    seen_arrival_[sequence % kSize] = arrivals_;
}

SequenceWindow::Verdict SequenceWindow::repeat(uint32_t slot, uint64_t now_ns) const {
    const uint64_t first_ns = seen_at_[slot];
    const uint64_t elapsed_ns = now_ns > first_ns ? now_ns - first_ns : 0;
    const uint64_t between = arrivals_ - seen_arrival_[slot] - 1;
    return elapsed_ns < horizon_ns_ || between < kDuplicateArrivals ? Verdict::Duplicate : Verdict::Replayed;
}

SequenceWindow::Verdict SequenceWindow::check(uint32_t sequence, uint64_t now_ns) {
    ++arrivals_;
    if (!started_) {
        started_ = true;
        highest_ = sequence;
        mark(sequence, now_ns);
        return Verdict::Fresh;
    }
    // Signed distance modulo 2^32, so the window works across the wrap of the counter.
    const int64_t ahead = static_cast<int32_t>(sequence - highest_);
    if (ahead > 0) {
        if (ahead >= static_cast<int64_t>(kSize)) {
            seen_.reset();
        } else {
            for (uint32_t s = highest_ + 1; s != sequence; ++s) seen_.reset(s % kSize);
        }
        highest_ = sequence;
        mark(sequence, now_ns);
        return Verdict::Fresh;
    }
    if (-ahead >= static_cast<int64_t>(kSize)) return Verdict::Replayed;  // older than the window
    const uint32_t slot = sequence % kSize;
    if (seen_.test(slot)) return repeat(slot, now_ns);
    mark(sequence, now_ns);
    return Verdict::Reordered;
}

const char* sequence_verdict_name(SequenceWindow::Verdict v) {
    switch (v) {
        case SequenceWindow::Verdict::Fresh:
            return "fresh";
        case SequenceWindow::Verdict::Reordered:
            return "reordered";
        case SequenceWindow::Verdict::Duplicate:
            return "duplicate";
        case SequenceWindow::Verdict::Replayed:
            return "replayed";
    }
    return "?";
}

}  // namespace cupola

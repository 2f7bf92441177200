#include "wire/sequence_window.hpp"

namespace cupola {

void SequenceWindow::mark(uint32_t sequence, uint64_t now_ns) {
    seen_.set(sequence % kSize);
    seen_at_[sequence % kSize] = now_ns;
}

SequenceWindow::Verdict SequenceWindow::check(uint32_t sequence, uint64_t now_ns) {
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
    if (seen_.test(slot)) return now_ns - seen_at_[slot] < horizon_ns_ ? Verdict::Duplicate : Verdict::Replayed;
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

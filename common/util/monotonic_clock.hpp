#pragma once
// CLOCK_MONOTONIC in nanoseconds: comparable between processes on one host (loopback latency).
#include <time.h>

#include <cstdint>

namespace cupola {
inline uint64_t monotonic_ns() {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<uint64_t>(ts.tv_sec) * 1000000000ull + static_cast<uint64_t>(ts.tv_nsec);
}
}  // namespace cupola

#pragma once
// The one receive-until-deadline step of both nodes: waits for the next message no longer than to
// `deadline`, and never longer than kMaxReceiveWait, so a node loop comes back to its session's
// time-driven steps (resends, hello rules, stats) at least that often.
#include <algorithm>
#include <chrono>
#include <optional>

#include "net/wire_endpoint.hpp"

namespace cupola {

constexpr std::chrono::milliseconds kMaxReceiveWait{100};

// The wait in whole milliseconds (truncated) for a deadline, in [0, kMaxReceiveWait].
inline int receive_wait_ms(std::chrono::steady_clock::time_point now, std::chrono::steady_clock::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count();
    return static_cast<int>(std::clamp<long long>(left, 0, kMaxReceiveWait.count()));
}

inline std::optional<ReceivedMessage> receive_until(WireEndpoint& wire,
                                                    std::chrono::steady_clock::time_point deadline) {
    return wire.receive(receive_wait_ms(std::chrono::steady_clock::now(), deadline));
}

// What already waits in the socket, without waiting.
inline std::optional<ReceivedMessage> receive_queued(WireEndpoint& wire) { return wire.receive(0); }

}  // namespace cupola

#pragma once
// Puts fragmented messages back together. Keyed by (sender, session, type, frame), so the
// fragments of a restarted sender's message never mix with its old ones; a message whose
// fragments do not all arrive is evicted (and counted) once `max_pending` newer messages exist.
#include <cstdint>
#include <map>
#include <optional>
#include <tuple>
#include <vector>

#include "wire/packet.hpp"

namespace cupola {

struct Message {
    PacketType type;
    uint16_t sender;
    uint64_t frame;
    std::vector<uint8_t> payload;
    uint64_t session = 0;  // the sender's session nonce
};

class Reassembler {
public:
    explicit Reassembler(size_t max_pending = 8) : max_pending_(max_pending > 0 ? max_pending : 1) {}

    // Returns the whole message when this packet completes it. Inconsistent fragments (a length
    // or count that disagrees with earlier fragments of the same message) are counted as bad.
    std::optional<Message> add(Packet&& p);

    uint64_t incomplete_dropped() const { return incomplete_dropped_; }
    uint64_t inconsistent() const { return inconsistent_; }
    uint64_t duplicates() const { return duplicates_; }

private:
    struct Pending {
        uint32_t length = 0;
        uint16_t count = 0;
        std::vector<uint8_t> data;
        std::vector<bool> have;
        uint16_t received = 0;
        uint64_t arrival = 0;
    };
    using Key = std::tuple<uint16_t, uint64_t, uint8_t, uint64_t>;
    std::map<Key, Pending> pending_;
    size_t max_pending_;
    uint64_t arrivals_ = 0;
    uint64_t incomplete_dropped_ = 0;
    uint64_t inconsistent_ = 0;
    uint64_t duplicates_ = 0;
};

}  // namespace cupola

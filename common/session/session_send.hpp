#pragma once
// A datagram a session asks its node to send: the master's go to every snapshot destination, a
// slave's to the master's report address; `to_session` is the session it answers (0: anyone).
#include <cstdint>
#include <vector>

#include "wire/packet.hpp"

namespace cupola {

struct SessionSend {
    PacketType type = PacketType::Hello;
    uint64_t frame = 0;
    std::vector<uint8_t> payload;
    uint64_t to_session = 0;
};

}  // namespace cupola

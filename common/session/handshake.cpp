#include "session/handshake.hpp"

namespace cupola {

SessionGuard::OpenPolicy master_open_policy(uint64_t self) {
    return [self](const PacketHeader& h) {
        if (h.sender == kMasterSender) return SessionOpen::Ignore;  // our own multicast, looped back
        if (h.type != PacketType::Hello) return SessionOpen::Reject;
        return h.to_session == self ? SessionOpen::Open : SessionOpen::Unverified;
    };
}

SessionGuard::OpenPolicy slave_open_policy(uint64_t self) {
    return [self](const PacketHeader& h) {
        if (h.sender != kMasterSender) return SessionOpen::Ignore;  // another node's traffic
        if (h.type == PacketType::Welcome && h.to_session == self) return SessionOpen::Open;
        return SessionOpen::Unverified;
    };
}

}  // namespace cupola

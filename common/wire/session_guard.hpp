#pragma once
// Which authentic datagrams a node acts on. Every process draws a random session nonce when it
// starts and writes it into every datagram; the datagrams of one session carry consecutive
// sequence numbers. For each peer (sender id) the guard keeps the peer's current session and a
// SequenceWindow over it, plus the sessions that peer used before (they ended with a restart).
//
// A peer's new session is established only by the handshake, so a recording of an old session
// can never be mistaken for a new one:
//   slave  -> master  Hello(to_session = 0)            the master answers, acts on nothing else
//   master -> slave   Welcome(to_session = slave's)    the slave now trusts the master's session
//   slave  -> master  Hello(to_session = master's)     the master now trusts the slave's session
// The roles differ only in the open policy each node gives the guard. Packets addressed to a
// session (to_session) other than ours are stale: we restarted since they were sent.
#include <cstdint>
#include <deque>
#include <functional>
#include <map>

#include "wire/packet.hpp"
#include "wire/sequence_window.hpp"

namespace cupola {

// What a node wants done with an authentic datagram from a session it has not established.
enum class SessionOpen {
    Open,        // establish it now (the handshake's proof is in this datagram)
    Unverified,  // pass it up marked unverified (a Hello to answer, a sign that the master restarted)
    Reject,      // drop and count as UnknownSession
    Ignore,      // drop silently: normal traffic not meant for us
};

struct GuardVerdict {
    enum Kind { Accept, Opened, Unverified, Duplicate, Ignored, Rejected } kind = Rejected;
    RejectReason reason = RejectReason::UnknownSession;  // when Rejected
    bool reordered = false;                              // Accept/Opened: arrived after a later datagram
};

class SessionGuard {
public:
    using OpenPolicy = std::function<SessionOpen(const PacketHeader&)>;

    // self_session: this process's nonce; `retired_kept`: ended sessions remembered per peer.
    SessionGuard(uint64_t self_session, OpenPolicy policy, size_t retired_kept = 16);

    GuardVerdict check(const PacketHeader& h, uint64_t now_ns);

    uint64_t self_session() const { return self_; }
    // The peer's established session (0: none).
    uint64_t peer_session(uint16_t sender) const;

private:
    struct Peer {
        uint64_t session = 0;
        SequenceWindow window;
        std::deque<uint64_t> retired;
    };
    uint64_t self_;
    OpenPolicy policy_;
    size_t retired_kept_;
    std::map<uint16_t, Peer> peers_;
};

}  // namespace cupola

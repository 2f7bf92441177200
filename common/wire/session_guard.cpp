#include "wire/session_guard.hpp"

#include <algorithm>

namespace cupola {

SessionGuard::SessionGuard(uint64_t self_session, OpenPolicy policy, size_t retired_kept)
    : self_(self_session), policy_(std::move(policy)), retired_kept_(retired_kept) {}

uint64_t SessionGuard::peer_session(uint16_t sender) const {
    auto it = peers_.find(sender);
    return it == peers_.end() ? 0 : it->second.session;
}

GuardVerdict SessionGuard::check(const PacketHeader& h, uint64_t now_ns) {
    GuardVerdict v;
    auto reject = [&](RejectReason r) {
        v.kind = GuardVerdict::Rejected;
        v.reason = r;
        return v;
    };
    if (h.to_session != 0 && h.to_session != self_) {
        // A welcome for another slave process is normal multicast traffic; anything else
        // addressed to another session of ours predates our start.
        if (h.type == PacketType::Welcome) {
            v.kind = GuardVerdict::Ignored;
            return v;
        }
        return reject(RejectReason::StaleSession);
    }
    if (h.session == 0) return reject(RejectReason::UnknownSession);
    Peer& peer = peers_[h.sender];
    auto sequence = [&](GuardVerdict::Kind accepted) {
        switch (peer.window.check(h.sequence, now_ns)) {
            case SequenceWindow::Verdict::Fresh:
                v.kind = accepted;
                return v;
            case SequenceWindow::Verdict::Reordered:
                v.kind = accepted;
                v.reordered = true;
                return v;
            case SequenceWindow::Verdict::Duplicate:
                v.kind = GuardVerdict::Duplicate;
                return v;
            case SequenceWindow::Verdict::Replayed:
                break;
        }
        return reject(RejectReason::Replayed);
    };
    if (peer.session != 0 && h.session == peer.session) return sequence(GuardVerdict::Accept);
    if (std::find(peer.retired.begin(), peer.retired.end(), h.session) != peer.retired.end())
        return reject(RejectReason::StaleSession);
    switch (policy_(h)) {
        case SessionOpen::Open:
            if (peer.session != 0) {
                peer.retired.push_back(peer.session);
                if (peer.retired.size() > retired_kept_) peer.retired.pop_front();
            }
            peer.session = h.session;
            peer.window = SequenceWindow();
            return sequence(GuardVerdict::Opened);
        case SessionOpen::Unverified:
            v.kind = GuardVerdict::Unverified;
            return v;
        case SessionOpen::Ignore:
            v.kind = GuardVerdict::Ignored;
            return v;
        case SessionOpen::Reject:
            break;
    }
    return reject(RejectReason::UnknownSession);
}

}  // namespace cupola

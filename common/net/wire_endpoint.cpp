#include "net/wire_endpoint.hpp"

#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstring>
#include <sstream>

#include "session/handshake.hpp"
#include "util/monotonic_clock.hpp"

namespace cupola {

uint64_t WireCounters::total_rejected() const {
    uint64_t t = 0;
    for (auto v : rejected) t += v;
    return t;
}

uint64_t WireCounters::foreign() const {
    return rejected_for(RejectReason::BadMagic) + rejected_for(RejectReason::BadVersion) +
           rejected_for(RejectReason::WrongCluster);
}

uint64_t WireCounters::malformed() const {
    return rejected_for(RejectReason::BadLength) + rejected_for(RejectReason::BadType) +
           rejected_for(RejectReason::BadFragment);
}

std::string WireCounters::summary() const {
    std::ostringstream os;
    os << "received " << datagrams_received << " datagrams / " << messages_received << " messages, sent "
       << datagrams_sent << " (" << send_failures << " failed), duplicates " << duplicates << ", reordered "
       << reordered << ", incomplete " << incomplete << ", rejected " << total_rejected();
    bool first = true;
    for (size_t i = 0; i < rejected.size(); ++i) {
        if (!rejected[i]) continue;
        os << (first ? " (" : ", ") << reject_reason_name(static_cast<RejectReason>(i)) << " " << rejected[i];
        first = false;
    }
    if (!first) os << ")";
    return os.str();
}

nlohmann::json WireCounters::to_json() const {
    nlohmann::json by_reason = nlohmann::json::object();
    for (size_t i = 0; i < rejected.size(); ++i)
        by_reason[reject_reason_name(static_cast<RejectReason>(i))] = rejected[i];
    return {{"datagrams_received", datagrams_received},
            {"datagrams_sent", datagrams_sent},
            {"messages_received", messages_received},
            {"duplicates", duplicates},
            {"reordered", reordered},
            {"incomplete", incomplete},
            {"send_failures", send_failures},
            {"sessions_opened", sessions_opened},
            {"unverified", unverified},
            {"ignored", ignored},
            {"forged", forged()},
            {"foreign", foreign()},
            {"malformed", malformed()},
            {"replayed", rejected_for(RejectReason::Replayed)},
            {"stale_session", rejected_for(RejectReason::StaleSession)},
            {"unknown_session", rejected_for(RejectReason::UnknownSession)},
            {"rejected", total_rejected()},
            {"rejected_by_reason", by_reason}};
}

WireEndpoint::WireEndpoint(UdpSocket socket, PacketCodec codec, SessionGuard::OpenPolicy policy, uint16_t self,
                           size_t max_datagram, std::string log_name)
    : socket_(std::move(socket)),
      codec_(codec),
      guard_(codec.session(), std::move(policy)),
      self_(self),
      max_datagram_(max_datagram),
      log_name_(std::move(log_name)) {}

void WireEndpoint::send(PacketType type, uint64_t frame, const std::vector<uint8_t>& payload,
                        const std::vector<sockaddr_in>& destinations, uint64_t to_session) {
    auto datagrams = codec_.encode(type, self_, frame, payload, max_datagram_, &sequence_, to_session);
    for (const auto& to : destinations)
        for (const auto& d : datagrams) {
            if (socket_.send_to(to, d.data(), d.size())) {
                ++counters_.datagrams_sent;
                continue;
            }
            const int err = errno;
            if (++counters_.send_failures <= 3 || counters_.send_failures % 100 == 0)
                spdlog::warn("{}: could not send to {}: {} ({} datagrams so far); the protocol will retry", log_name_,
                             to_string(to), std::strerror(err), counters_.send_failures);
        }
}

void WireEndpoint::count_reject(RejectReason r, const sockaddr_in& from) {
    uint64_t n = ++counters_.rejected[static_cast<size_t>(r)];
    // Every rejected datagram is counted; the log shows the first few of each kind, then every 100th.
    if (n <= 3 || n % 100 == 0)
        spdlog::warn("{}: dropped datagram from {}: {} ({} so far of this kind)", log_name_, to_string(from),
                     reject_reason_name(r), n);
}

std::optional<ReceivedMessage> WireEndpoint::receive(int timeout_ms) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    for (;;) {
        int left = static_cast<int>(
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count());
        auto d = socket_.receive(std::max(0, left));
        if (!d) return std::nullopt;
        ++counters_.datagrams_received;
        DecodeResult r = codec_.decode(d->data.data(), d->data.size());
        if (!r.packet) {
            count_reject(r.reason, d->from);
            continue;
        }
        const PacketHeader& h = r.packet->header;
        // As of its arrival, not of this read: a network duplicate that waited in the queue
        // while this process rendered is still a duplicate, not a replay.
        const GuardVerdict g = guard_.check(h, monotonic_ns() - d->queued_ns);
        switch (g.kind) {
            case GuardVerdict::Rejected:
                count_reject(g.reason, d->from);
                continue;
            case GuardVerdict::Duplicate:
                ++counters_.duplicates;
                continue;
            case GuardVerdict::Ignored:
                ++counters_.ignored;
                continue;
            case GuardVerdict::Unverified: {
                // Authentic, but its session is not established: pass it up for the handshake only.
                ++counters_.unverified;
                ReceivedMessage um;
                um.message = Message{h.type, h.sender, h.frame, std::vector<uint8_t>{}, h.session};
                if (h.fragment_count == 1) um.message.payload = std::move(r.packet->payload);
                um.from = d->from;
                um.verified = false;
                um.to_session = h.to_session;
                return um;
            }
            case GuardVerdict::Accept:
            case GuardVerdict::Opened:
                break;
        }
        if (g.reordered) ++counters_.reordered;
        const bool opened = g.kind == GuardVerdict::Opened;
        const uint64_t to_session = h.to_session;
        if (opened) {
            ++counters_.sessions_opened;
            spdlog::info("{}: {} {} established session {:016x} from {}", log_name_,
                         h.sender == kMasterSender ? "master" : "channel",
                         h.sender == kMasterSender ? "" : std::to_string(h.sender), h.session, to_string(d->from));
        }
        const uint64_t inconsistent_before = reassembler_.inconsistent();
        const uint64_t incomplete_before = reassembler_.incomplete_dropped();
        auto m = reassembler_.add(std::move(*r.packet));
        if (reassembler_.inconsistent() != inconsistent_before) count_reject(RejectReason::BadFragment, d->from);
        counters_.incomplete += reassembler_.incomplete_dropped() - incomplete_before;
        if (m) {
            ++counters_.messages_received;
            ReceivedMessage rm;
            rm.message = std::move(*m);
            rm.from = d->from;
            rm.opened = opened;
            rm.to_session = to_session;
            return rm;
        }
        if (opened) {
            // The session is established even though this datagram did not complete a message.
            ReceivedMessage rm;
            rm.message = Message{h.type, h.sender, h.frame, std::vector<uint8_t>{}, h.session};
            rm.from = d->from;
            rm.opened = true;
            rm.verified = false;
            rm.to_session = to_session;
            return rm;
        }
    }
}

std::vector<sockaddr_in> snapshot_destinations(const ClusterConfig& cfg) {
    const auto& n = cfg.network;
    switch (n.transport) {
        case Transport::Multicast:
            return {make_address(n.multicast_group, n.snapshot_port)};
        case Transport::Broadcast:
            return {make_address(n.broadcast_address, n.snapshot_port)};
        case Transport::Unicast: {
            std::vector<sockaddr_in> out;
            for (const auto& c : cfg.channels) out.push_back(parse_host_port(c.unicast_address));
            return out;
        }
    }
    return {};
}

sockaddr_in master_report_address(const ClusterConfig& cfg) {
    return make_address(cfg.network.master_address, cfg.network.report_port);
}

WireEndpoint open_master_endpoint(const ClusterConfig& cfg, const AuthKey& key, uint64_t session) {
    UdpSocket s;
    s.bind(master_report_address(cfg));
    s.set_receive_buffer(1 << 20);
    if (cfg.network.transport == Transport::Multicast) s.set_multicast_sender(cfg.network.interface_address);
    if (cfg.network.transport == Transport::Broadcast) s.enable_broadcast();
    return WireEndpoint(std::move(s), PacketCodec(cfg.cluster_id, key, session), master_open_policy(session),
                        kMasterSender, static_cast<size_t>(cfg.network.max_datagram_bytes), "master");
}

WireEndpoint open_slave_endpoint(const ClusterConfig& cfg, const ChannelConfig& channel, const AuthKey& key,
                                 uint64_t session) {
    const auto& n = cfg.network;
    UdpSocket s;
    s.set_receive_buffer(4 << 20);
    switch (n.transport) {
        case Transport::Multicast:
            s.set_reuse_address();
            s.bind(make_address(n.multicast_group, n.snapshot_port));
            s.join_multicast(n.multicast_group, n.interface_address);
            break;
        case Transport::Broadcast:
            s.set_reuse_address();
            s.bind(make_address("0.0.0.0", n.snapshot_port));
            break;
        case Transport::Unicast:
            s.bind(parse_host_port(channel.unicast_address));
            break;
    }
    return WireEndpoint(std::move(s), PacketCodec(cfg.cluster_id, key, session), slave_open_policy(session),
                        static_cast<uint16_t>(channel.id), static_cast<size_t>(n.max_datagram_bytes),
                        "slave " + channel.name);
}

}  // namespace cupola

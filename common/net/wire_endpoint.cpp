#include "net/wire_endpoint.hpp"

#include <spdlog/spdlog.h>

#include <sstream>

namespace cupola {

uint64_t WireCounters::total_rejected() const {
    uint64_t t = 0;
    for (auto v : rejected) t += v;
    return t;
}

std::string WireCounters::summary() const {
    std::ostringstream os;
    os << "received " << datagrams_received << " datagrams / " << messages_received << " messages, sent "
       << datagrams_sent << ", rejected " << total_rejected();
    bool first = true;
    for (size_t i = 0; i < rejected.size(); ++i) {
        if (!rejected[i]) continue;
        os << (first ? " (" : ", ") << reject_reason_name(static_cast<RejectReason>(i)) << " " << rejected[i];
        first = false;
    }
    if (!first) os << ")";
    return os.str();
}

WireEndpoint::WireEndpoint(UdpSocket socket, PacketCodec codec, uint16_t self, size_t max_datagram,
                           std::string log_name)
    : socket_(std::move(socket)), codec_(codec), self_(self), max_datagram_(max_datagram), log_name_(std::move(log_name)) {}

void WireEndpoint::send(PacketType type, uint64_t frame, const std::vector<uint8_t>& payload,
                        const std::vector<sockaddr_in>& destinations) {
    auto datagrams = codec_.encode(type, self_, frame, payload, max_datagram_, &sequence_);
    for (const auto& to : destinations)
        for (const auto& d : datagrams) {
            socket_.send_to(to, d.data(), d.size());
            ++counters_.datagrams_sent;
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
        const uint64_t inconsistent_before = reassembler_.inconsistent();
        auto m = reassembler_.add(std::move(*r.packet));
        if (reassembler_.inconsistent() != inconsistent_before) count_reject(RejectReason::BadFragment, d->from);
        if (m) {
            ++counters_.messages_received;
            return ReceivedMessage{std::move(*m), d->from};
        }
    }
}

std::vector<sockaddr_in> snapshot_destinations(const ClusterConfig& cfg) {
    const auto& n = cfg.network;
    switch (n.transport) {
        case Transport::Multicast: return {make_address(n.multicast_group, n.snapshot_port)};
        case Transport::Broadcast: return {make_address(n.broadcast_address, n.snapshot_port)};
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

WireEndpoint open_master_endpoint(const ClusterConfig& cfg, const AuthKey& key) {
    UdpSocket s;
    s.bind(master_report_address(cfg));
    s.set_receive_buffer(1 << 20);
    if (cfg.network.transport == Transport::Multicast) s.set_multicast_sender(cfg.network.interface_address);
    if (cfg.network.transport == Transport::Broadcast) s.enable_broadcast();
    return WireEndpoint(std::move(s), PacketCodec(cfg.cluster_id, key), kMasterSender,
                        static_cast<size_t>(cfg.network.max_datagram_bytes), "master");
}

WireEndpoint open_slave_endpoint(const ClusterConfig& cfg, const ChannelConfig& channel, const AuthKey& key) {
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
    return WireEndpoint(std::move(s), PacketCodec(cfg.cluster_id, key), static_cast<uint16_t>(channel.id),
                        static_cast<size_t>(n.max_datagram_bytes), "slave " + channel.name);
}

}  // namespace cupola

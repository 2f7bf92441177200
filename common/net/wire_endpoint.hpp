#pragma once
// A UDP socket speaking the Cupola wire protocol: authenticates and reassembles incoming
// datagrams, counts and logs every rejected one by reason, fragments and signs outgoing messages.
#include <array>
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "config/cluster_config.hpp"
#include "net/udp_socket.hpp"
#include "wire/packet.hpp"
#include "wire/reassembler.hpp"

namespace cupola {

struct WireCounters {
    uint64_t datagrams_received = 0;
    uint64_t datagrams_sent = 0;
    uint64_t messages_received = 0;
    std::array<uint64_t, static_cast<size_t>(RejectReason::Count)> rejected{};
    uint64_t total_rejected() const;
    std::string summary() const;  // "rejected: 3 (bad magic 1, authentication failed 2), ..."
};

struct ReceivedMessage {
    Message message;
    sockaddr_in from{};
};

class WireEndpoint {
public:
    WireEndpoint(UdpSocket socket, PacketCodec codec, uint16_t self, size_t max_datagram, std::string log_name);

    void send(PacketType type, uint64_t frame, const std::vector<uint8_t>& payload,
              const std::vector<sockaddr_in>& destinations);

    // Waits up to timeout_ms for the next whole, authentic message; rejected datagrams are
    // counted and skipped while the wait goes on.
    std::optional<ReceivedMessage> receive(int timeout_ms);

    const WireCounters& counters() const { return counters_; }
    const Reassembler& reassembler() const { return reassembler_; }
    UdpSocket& socket() { return socket_; }

private:
    void count_reject(RejectReason r, const sockaddr_in& from);

    UdpSocket socket_;
    PacketCodec codec_;
    Reassembler reassembler_;
    uint16_t self_;
    size_t max_datagram_;
    uint32_t sequence_ = 0;
    std::string log_name_;
    WireCounters counters_;
};

// Endpoint of the master: bound to master_address:report_port, sending snapshots by the
// configured transport. destinations() lists where a snapshot goes.
WireEndpoint open_master_endpoint(const ClusterConfig& cfg, const AuthKey& key);
std::vector<sockaddr_in> snapshot_destinations(const ClusterConfig& cfg);

// Endpoint of a slave: receives snapshots for `channel` by the configured transport and sends
// its reports to master_address:report_port.
WireEndpoint open_slave_endpoint(const ClusterConfig& cfg, const ChannelConfig& channel, const AuthKey& key);
sockaddr_in master_report_address(const ClusterConfig& cfg);

}  // namespace cupola

#pragma once
// A UDP socket speaking the Cupola wire protocol: authenticates incoming datagrams, passes them
// through the session guard (replay window, restarts), reassembles them, counts and logs every
// anomaly by kind, and fragments and signs outgoing messages with this process's session nonce.
#include <array>
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "config/cluster_config.hpp"
#include "net/udp_socket.hpp"
#include <nlohmann/json.hpp>

#include "wire/packet.hpp"
#include "wire/reassembler.hpp"
#include "wire/session_guard.hpp"

namespace cupola {

struct WireCounters {
    uint64_t datagrams_received = 0;
    uint64_t datagrams_sent = 0;
    uint64_t messages_received = 0;
    std::array<uint64_t, static_cast<size_t>(RejectReason::Count)> rejected{};
    uint64_t duplicates = 0;       // a datagram repeated by the network (dropped)
    uint64_t reordered = 0;        // accepted after a later datagram of the same sender
    uint64_t incomplete = 0;       // messages given up with fragments missing
    uint64_t send_failures = 0;    // datagrams the network refused to take (link down, no route)
    uint64_t sessions_opened = 0;  // peers (re)established through the handshake
    uint64_t unverified = 0;       // authentic datagrams of a session not established yet
    uint64_t ignored = 0;          // welcomes meant for other processes
    uint64_t total_rejected() const;
    uint64_t rejected_for(RejectReason r) const { return rejected[static_cast<size_t>(r)]; }
    // The kinds an operator asks about: forged = failed authentication; foreign = other
    // cluster, version or protocol; malformed = bad lengths, types or fragments.
    uint64_t forged() const { return rejected_for(RejectReason::BadAuth); }
    uint64_t foreign() const;
    uint64_t malformed() const;
    std::string summary() const;  // "received ..., rejected 3 (bad magic 1, authentication failed 2), ..."
    nlohmann::json to_json() const;
};

struct ReceivedMessage {
    Message message;
    sockaddr_in from{};
    // false: authentic, but from a session not established yet (see SessionGuard); the payload is
    // only there for single-datagram messages. Never act on it beyond the handshake.
    bool verified = true;
    bool opened = false;      // this message established its sender's (new) session
    uint64_t to_session = 0;  // the session of ours it was addressed to (0: anyone)
};

class WireEndpoint {
public:
    // codec: cluster, key and this process's session; policy: which unknown peer sessions may open.
    WireEndpoint(UdpSocket socket, PacketCodec codec, SessionGuard::OpenPolicy policy, uint16_t self,
                 size_t max_datagram, std::string log_name);

    // to_session: the addressee's session this message answers (0: anyone).
    void send(PacketType type, uint64_t frame, const std::vector<uint8_t>& payload,
              const std::vector<sockaddr_in>& destinations, uint64_t to_session = 0);

    // Waits up to timeout_ms for the next whole, authentic message; rejected datagrams are
    // counted and skipped while the wait goes on.
    std::optional<ReceivedMessage> receive(int timeout_ms);

    const WireCounters& counters() const { return counters_; }
    const Reassembler& reassembler() const { return reassembler_; }
    UdpSocket& socket() { return socket_; }
    uint64_t session() const { return codec_.session(); }
    uint64_t peer_session(uint16_t sender) const { return guard_.peer_session(sender); }

private:
    void count_reject(RejectReason r, const sockaddr_in& from);

    UdpSocket socket_;
    PacketCodec codec_;
    SessionGuard guard_;
    Reassembler reassembler_;
    uint16_t self_;
    size_t max_datagram_;
    uint32_t sequence_ = 0;
    std::string log_name_;
    WireCounters counters_;
};

// Endpoint of the master: bound to master_address:report_port, sending snapshots by the
// configured transport. destinations() lists where a snapshot goes. It establishes a slave's
// session on a Hello addressed to its own session, and passes other Hellos up unverified.
WireEndpoint open_master_endpoint(const ClusterConfig& cfg, const AuthKey& key, uint64_t session);
std::vector<sockaddr_in> snapshot_destinations(const ClusterConfig& cfg);

// Endpoint of a slave: receives snapshots for `channel` by the configured transport and sends
// its reports to master_address:report_port. It establishes the master's session on a Welcome
// addressed to its own session, and passes the master's other packets up unverified until then.
WireEndpoint open_slave_endpoint(const ClusterConfig& cfg, const ChannelConfig& channel, const AuthKey& key,
                                 uint64_t session);
sockaddr_in master_report_address(const ClusterConfig& cfg);

}  // namespace cupola

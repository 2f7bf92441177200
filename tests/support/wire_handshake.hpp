#pragma once
// The join handshake (wire/session_guard.hpp) played between endpoints of one test process:
// tests that act as the master, or as master and slaves, must complete it before the other side
// acts on their packets, exactly as the real processes do.
#include <chrono>
#include <vector>

#include "config/cluster_config.hpp"
#include "net/wire_endpoint.hpp"
#include "wire/reports.hpp"

namespace cupola::test {

// Master side: answers hellos from unknown processes with a welcome until a slave process
// completes the handshake; returns its channel id, or -1 after timeout_ms.
inline int welcome_one_slave(WireEndpoint& master, const ClusterConfig& cfg, int timeout_ms) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (std::chrono::steady_clock::now() < until) {
        auto m = master.receive(100);
        if (!m || m->message.type != PacketType::Hello) continue;
        if (m->opened) return m->message.sender;
        if (m->to_session != master.session()) {
            const HelloMessage h = decode_hello(m->message.payload);
            master.send(PacketType::Welcome, 0, encode_welcome({h.channel, 0}), snapshot_destinations(cfg),
                        m->message.session);
        }
    }
    return -1;
}

// Both sides in this process: every slave endpoint says hello, is welcomed and confirms.
inline bool handshake(WireEndpoint& master, std::vector<WireEndpoint>& slaves, const ClusterConfig& cfg) {
    for (size_t i = 0; i < slaves.size(); ++i) {
        HelloMessage h;
        h.channel = static_cast<uint16_t>(cfg.channels[i].id);
        slaves[i].send(PacketType::Hello, 0, encode_hello(h), {master_report_address(cfg)}, 0);
        auto hello = master.receive(2000);
        if (!hello || hello->verified || hello->message.type != PacketType::Hello) return false;
        master.send(PacketType::Welcome, 0, encode_welcome({h.channel, 0}), snapshot_destinations(cfg),
                    hello->message.session);
        // Every slave may see the welcome (multicast); only the addressee is opened by it.
        std::optional<ReceivedMessage> welcome;
        for (int tries = 0; tries < 4 && !welcome; ++tries) welcome = slaves[i].receive(2000);
        if (!welcome || !welcome->opened) return false;
        slaves[i].send(PacketType::Hello, 0, encode_hello(h), {master_report_address(cfg)}, master.session());
        auto confirm = master.receive(2000);
        if (!confirm || !confirm->opened) return false;
    }
    return true;
}

}  // namespace cupola::test

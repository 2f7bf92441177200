#pragma once
// The join handshake (wire/session_guard.hpp) played between endpoints of one test process by the
// nodes' own session code (MasterSession, SlaveSession): tests that act as the master, or as master
// and slaves, complete it before the other side acts on their packets, exactly as the processes do.
#include <unistd.h>

#include <chrono>
#include <vector>

#include "config/cluster_config.hpp"
#include "net/wire_endpoint.hpp"
#include "session/master_session.hpp"
#include "session/receive_until.hpp"
#include "session/slave_session.hpp"

namespace cupola::test {

inline MasterSession master_session_for(const ClusterConfig& cfg, uint64_t session) {
    std::vector<int> ids;
    for (const auto& c : cfg.channels) ids.push_back(c.id);
    return MasterSession(ids, session,
                         {std::chrono::milliseconds(cfg.network.resend_interval_ms),
                          std::chrono::milliseconds(cfg.network.channel_timeout_ms)});
}

inline SlaveSession slave_session_for(const ChannelConfig& channel, std::chrono::seconds idle_timeout) {
    SlaveSessionConfig c;
    c.channel = channel.id;
    c.process_id = static_cast<uint32_t>(::getpid());
    c.idle_timeout = idle_timeout;
    c.log_name = "test slave " + channel.name;
    return SlaveSession(c, std::chrono::steady_clock::now());
}

inline void send_all(WireEndpoint& master, const ClusterConfig& cfg, const MasterActions& a) {
    for (const MasterSend& s : a.sends)
        master.send(s.type, s.frame, s.payload, snapshot_destinations(cfg), s.to_session);
}

inline void send_all(WireEndpoint& slave, const ClusterConfig& cfg, const SlaveActions& a) {
    for (const SlaveSend& s : a.sends)
        slave.send(s.type, s.frame, s.payload, {master_report_address(cfg)}, s.to_session);
}

// Master side: a MasterSession answers hellos from unknown processes with welcomes until a slave
// process completes the handshake; returns its channel id, or -1 after timeout_ms.
inline int welcome_one_slave(WireEndpoint& master, const ClusterConfig& cfg, int timeout_ms) {
    MasterSession session = master_session_for(cfg, master.session());
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (std::chrono::steady_clock::now() < until) {
        auto m = receive_until(master, until);
        if (!m) continue;
        const MasterActions a = session.on_message(*m, std::chrono::steady_clock::now());
        send_all(master, cfg, a);
        if (!a.joined.empty()) return a.joined.front();
    }
    return -1;
}

// Both sides in this process: each slave endpoint in turn joins through a SlaveSession while a
// MasterSession answers. What is left in the sockets afterwards (a hello or welcome repeated while
// the other side was slow) is dropped, so the caller starts from empty queues.
inline bool handshake(WireEndpoint& master, std::vector<WireEndpoint>& slaves, const ClusterConfig& cfg) {
    using Clock = std::chrono::steady_clock;
    MasterSession ms = master_session_for(cfg, master.session());
    for (size_t i = 0; i < slaves.size(); ++i) {
        SlaveSession ss = slave_session_for(cfg.channels[i], std::chrono::seconds(60));
        bool joined = false;
        const auto until = Clock::now() + std::chrono::seconds(6);
        while (!joined && Clock::now() < until) {
            send_all(slaves[i], cfg, ss.tick(Clock::now()));
            if (auto m = receive_until(master, Clock::now() + std::chrono::milliseconds(20))) {
                const MasterActions a = ms.on_message(*m, Clock::now());
                send_all(master, cfg, a);
                for (int id : a.joined) joined = joined || id == cfg.channels[i].id;
            }
            // Every slave may see the welcome (multicast); only the addressee is opened by it.
            if (auto m = receive_until(slaves[i], Clock::now() + std::chrono::milliseconds(20))) {
                ss.receive(std::move(*m));
                send_all(slaves[i], cfg, ss.step(Clock::now()));
            }
        }
        if (!joined) return false;
    }
    while (receive_queued(master)) {}
    for (auto& s : slaves)
        while (receive_queued(s)) {}
    return true;
}

}  // namespace cupola::test

// The protocol's state machines under hostile schedules (fuzz_protocol.hpp). Checked invariants:
//   * the master welcomes a channel at most every MasterSession::kWelcomeInterval, always addressed
//     to a process's session, naming the channel that said hello;
//   * a channel the master counts as joined is a configured one, and live afterwards;
//   * the reports a frame ends with are that frame's, each from the channel it is filed under;
//   * the master's quit ends within MasterSession::kQuitLimit plus one round;
//   * with the swap lock, the master's present names its current frame, only once the barrier let
//     it go; a slave shows only the frame it rendered last, at most once, before rendering the next;
//   * a slave sends only to session 0 or to the master session that welcomed it, renders a
//     snapshot whose hash is that of its content, and within one master session renders frames in
//     increasing order only; it leaves only with exit code 0 (quit) or 3 (idle).
#include "fuzz_protocol.hpp"

#include <cstdio>
#include <cstdlib>
#include <deque>
#include <map>
#include <optional>
#include <vector>

#include "session/handshake.hpp"
#include "session/master_session.hpp"
#include "session/slave_session.hpp"
#include "wire/reports.hpp"
#include "wire/session_guard.hpp"
#include "wire/snapshot.hpp"

namespace cupola::fuzz {
namespace {

using Clock = std::chrono::steady_clock;

[[noreturn]] void violated(const char* what) {
    std::fprintf(stderr, "cupola-fuzz-wire: protocol invariant violated: %s\n", what);
    std::fflush(stderr);
    std::abort();
}
#define PROTOCOL_CHECK(cond)          \
    do {                              \
        if (!(cond)) violated(#cond); \
    } while (0)

// One process's end of the wire.
struct Peer {
    Peer(uint16_t id, uint64_t session)
        : id(id),
          session(session),
          guard(session, id == kMasterSender ? master_open_policy(session) : slave_open_policy(session)) {}
    uint16_t id;
    uint64_t session;
    SessionGuard guard;
    uint32_t sequence = 0;
};

struct Datagram {
    int to = 0;  // slave index, or -1: the master
    PacketHeader header;
    std::vector<uint8_t> payload;
};

struct SlaveProcess {
    SlaveProcess(int channel, uint64_t session, Clock::time_point now)
        : peer(static_cast<uint16_t>(channel), session), session(config(channel), now) {}
    static SlaveSessionConfig config(int channel) {
        SlaveSessionConfig c;
        c.channel = channel;
        c.process_id = 1000 + static_cast<uint32_t>(channel);
        c.idle_timeout = std::chrono::seconds(30);
        return c;
    }
    Peer peer;
    SlaveSession session;
    bool exited = false;
    uint64_t rendered_master = 0;  // master session of the last render
    std::optional<uint64_t> rendered_frame;
    bool shown = true;  // the last render was shown (nothing to show before the first)
};

class Cluster {
public:
    explicit Cluster(int channels) : now_(Clock::time_point{} + std::chrono::hours(1)) {
        for (int i = 0; i < channels; ++i) {
            ids_.push_back(i);
            slaves_.emplace_back(i, nonce(), now_);
        }
        restart_master();
    }

    void restart_master() {
        master_peer_.emplace(kMasterSender, nonce());
        MasterTimings timings;
        timings.swap_lock = true;
        master_.emplace(ids_, master_peer_->session, timings);
        last_welcome_.clear();
        quit_started_.reset();
    }
    void restart_slave(size_t i) { slaves_[i] = SlaveProcess(static_cast<int>(i), nonce(), now_); }

    void tick(uint16_t dt_ms) {
        now_ += std::chrono::milliseconds(dt_ms);
        master_acts(master_->tick(now_));
        if (quit_started_ && !master_->quit_done())
            PROTOCOL_CHECK(now_ < *quit_started_ + MasterSession::kQuitLimit + MasterSession::kQuitRound);
        for (size_t i = 0; i < slaves_.size(); ++i) slave_acts(i, slaves_[i].session.tick(now_));
    }

    void next(bool lost) {
        if (flight_.empty()) return;
        Datagram d = std::move(flight_.front());
        flight_.pop_front();
        if (history_.size() < kMaxPool) history_.push_back(d);
        if (!lost) arrive(d);
    }
    void replay(uint16_t sel) {
        if (!history_.empty()) arrive(history_[sel % history_.size()]);
    }

    void frame() {
        const MasterPhase p = master_->phase();
        if (p == MasterPhase::Quitting || p == MasterPhase::Done) return;
        if (p == MasterPhase::Frame) {
            const uint64_t ended = master_->frame();
            for (const auto& [id, rep] : master_->end_frame()) {
                PROTOCOL_CHECK(rep.frame == ended);
                PROTOCOL_CHECK(rep.channel == id);
            }
        }
        Snapshot s;
        s.frame = next_frame_++;
        s.sim_time_s = static_cast<double>(s.frame) * 0.04;
        master_acts(master_->start_frame(s.frame, encode_snapshot(s), now_, 0));
    }
    void quit() {
        const MasterPhase p = master_->phase();
        if (p == MasterPhase::Quitting || p == MasterPhase::Done) return;
        quit_started_ = now_;
        master_acts(master_->start_quit(next_frame_, now_));
    }

    // type % (n + 1) == n: a new master process, else a new process for that slave.
    void restart(uint8_t who) {
        const size_t i = who % (slaves_.size() + 1);
        if (i == slaves_.size())
            restart_master();
        else
            restart_slave(i);
    }

    // An authentic message with a fuzz-chosen body from a process of the cluster (from_sel %
    // (n + 1) == n: the master), addressed to session 0 or (to_sel odd) to the receiver's.
    void forge(uint8_t type, uint8_t from_sel, uint8_t to_sel, uint16_t frame, std::vector<uint8_t> body) {
        static constexpr PacketType from_master[] = {PacketType::Snapshot, PacketType::Quit, PacketType::Welcome,
                                                     PacketType::Present};
        static constexpr PacketType from_slave[] = {PacketType::Hello, PacketType::FrameDone, PacketType::QuitAck,
                                                    PacketType::Heartbeat};
        const size_t from = from_sel % (slaves_.size() + 1);
        if (from == slaves_.size()) {
            const uint64_t to = to_sel & 1 ? slaves_[(to_sel >> 1) % slaves_.size()].peer.session : 0;
            send_from_master({from_master[type % 4], frame, std::move(body), to});
        } else {
            const uint64_t to = to_sel & 1 ? master_peer_->session : 0;
            send_from_slave(from, {from_slave[type % 4], frame, std::move(body), to});
        }
    }

private:
    uint64_t nonce() { return ++nonces_ * 0x9E3779B97F4A7C15ull; }

    std::optional<ReceivedMessage> through_guard(Peer& to, const Datagram& d) {
        const GuardVerdict v = to.guard.check(d.header, 0);
        if (v.kind != GuardVerdict::Accept && v.kind != GuardVerdict::Opened && v.kind != GuardVerdict::Unverified)
            return std::nullopt;
        ReceivedMessage rm;
        const PacketHeader& h = d.header;
        rm.message = Message{h.type, h.sender, h.frame, d.payload, h.session};
        rm.verified = v.kind != GuardVerdict::Unverified;
        rm.opened = v.kind == GuardVerdict::Opened;
        rm.to_session = h.to_session;
        return rm;
    }

    void arrive(const Datagram& d) {
        if (d.to < 0) {
            if (auto rm = through_guard(*master_peer_, d)) master_acts(master_->on_message(*rm, now_));
            return;
        }
        SlaveProcess& s = slaves_[static_cast<size_t>(d.to)];
        if (s.exited) return;
        if (auto rm = through_guard(s.peer, d)) {
            s.session.receive(std::move(*rm));
            slave_acts(static_cast<size_t>(d.to), s.session.step(now_));
        }
    }

    PacketHeader header(Peer& from, PacketType type, uint64_t frame, size_t size, uint64_t to_session) {
        PacketHeader h;
        h.type = type;
        h.sender = from.id;
        h.session = from.session;
        h.to_session = to_session;
        h.sequence = from.sequence++;
        h.frame = frame;
        h.message_length = h.payload_length = static_cast<uint32_t>(size);
        return h;
    }

    void send_from_master(const MasterSend& s) {
        const PacketHeader h = header(*master_peer_, s.type, s.frame, s.payload.size(), s.to_session);
        for (size_t i = 0; i < slaves_.size() && flight_.size() < kMaxPool; ++i)
            flight_.push_back({static_cast<int>(i), h, s.payload});
    }
    void send_from_slave(size_t i, const SlaveSend& s) {
        const PacketHeader h = header(slaves_[i].peer, s.type, s.frame, s.payload.size(), s.to_session);
        if (flight_.size() < kMaxPool) flight_.push_back({-1, h, s.payload});
    }

    void master_acts(const MasterActions& a) {
        for (const MasterSend& s : a.sends) {
            if (s.type == PacketType::Welcome) check_welcome(s);
            if (s.type == PacketType::Present) {
                PROTOCOL_CHECK(master_->presented());
                PROTOCOL_CHECK(s.frame == master_->frame());
                PROTOCOL_CHECK(decode_present(s.payload).frame == s.frame);
            }
            send_from_master(s);
        }
        for (int id : a.joined) {
            PROTOCOL_CHECK(id >= 0 && id < static_cast<int>(ids_.size()));
            PROTOCOL_CHECK(master_->barrier().state(id) == ChannelState::Live);
        }
    }
    void check_welcome(const MasterSend& s) {
        PROTOCOL_CHECK(s.to_session != 0);
        const WelcomeMessage w = decode_welcome(s.payload);
        PROTOCOL_CHECK(w.channel < ids_.size());
        auto last = last_welcome_.find(w.channel);
        PROTOCOL_CHECK(last == last_welcome_.end() || now_ - last->second >= MasterSession::kWelcomeInterval);
        last_welcome_[w.channel] = now_;
    }

    void slave_acts(size_t i, SlaveActions a) {
        SlaveProcess& s = slaves_[i];
        for (const SlaveSend& out : a.sends) {
            PROTOCOL_CHECK(out.to_session == 0 || out.to_session == s.session.master_session());
            send_from_slave(i, out);
        }
        if (a.present) {
            PROTOCOL_CHECK(!s.shown && s.rendered_frame && a.present->frame == *s.rendered_frame);
            s.shown = true;
            s.session.presented(a.present->frame, 1);
        }
        if (a.render) {
            PROTOCOL_CHECK(s.shown);  // the frame held is shown before the next render
            s.shown = false;
            PROTOCOL_CHECK(a.render->hash == snapshot_hash(encode_snapshot(a.render->snapshot)));
            if (s.rendered_frame && s.rendered_master == s.session.master_session())
                PROTOCOL_CHECK(a.render->snapshot.frame > *s.rendered_frame);
            s.rendered_master = s.session.master_session();
            s.rendered_frame = a.render->snapshot.frame;
            slave_acts(i, s.session.rendered(FrameReport{}, 0));
        }
        if (a.exit_code) {
            PROTOCOL_CHECK(*a.exit_code == 0 || *a.exit_code == 3);
            s.exited = true;
        }
    }

    Clock::time_point now_;
    uint64_t nonces_ = 0;
    std::vector<int> ids_;
    std::optional<Peer> master_peer_;
    std::optional<MasterSession> master_;
    std::vector<SlaveProcess> slaves_;
    std::deque<Datagram> flight_;
    std::vector<Datagram> history_;
    std::map<uint16_t, Clock::time_point> last_welcome_;
    std::optional<Clock::time_point> quit_started_;
    uint64_t next_frame_ = 0;
};

}  // namespace

void run_protocol(Reader& r) {
    Cluster c(1 + r.u8() % kMaxProtocolChannels);
    for (size_t step = 0; step < kMaxSteps && !r.empty(); ++step) {
        switch (static_cast<ProtocolOp>(r.u8() % kProtocolOpCount)) {
            case ProtocolOp::Tick:
                c.tick(r.u16());
                break;
            case ProtocolOp::Next:
                c.next(false);
                break;
            case ProtocolOp::Drop:
                c.next(true);
                break;
            case ProtocolOp::Replay:
                c.replay(r.u16());
                break;
            case ProtocolOp::Frame:
                c.frame();
                break;
            case ProtocolOp::Quit:
                c.quit();
                break;
            case ProtocolOp::Restart:
                c.restart(r.u8());
                break;
            case ProtocolOp::Forge: {
                const uint8_t type = r.u8(), from = r.u8(), to = r.u8();
                const uint16_t frame = r.u16();
                c.forge(type, from, to, frame, r.bytes(r.u16()));
                break;
            }
        }
    }
}

}  // namespace cupola::fuzz

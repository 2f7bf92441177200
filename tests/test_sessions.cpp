// MasterSession and SlaveSession (master/session/, common/session/): the protocol's state machines
// driven message by message and tick by tick, without sockets, EGL or threads. Datagrams between
// them pass the real SessionGuard with the endpoints' own open policies (session/handshake.hpp),
// so opened/verified/to_session are what a WireEndpoint would report.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <vector>

#include "session/handshake.hpp"
#include "session/master_session.hpp"
#include "session/slave_session.hpp"
#include "wire/reports.hpp"
#include "wire/session_guard.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

// One process's end of the wire: its nonce, its sender id, its guard and its sequence counter.
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

// A single-datagram message from `from` as `to`'s endpoint would pass it up (none: dropped).
std::optional<ReceivedMessage> deliver(Peer& from, Peer& to, PacketType type, uint64_t frame,
                                       const std::vector<uint8_t>& payload, uint64_t to_session,
                                       std::optional<uint32_t> sequence = std::nullopt) {
    PacketHeader h;
    h.type = type;
    h.sender = from.id;
    h.session = from.session;
    h.to_session = to_session;
    h.sequence = sequence ? *sequence : from.sequence++;
    h.frame = frame;
    h.message_length = h.payload_length = static_cast<uint32_t>(payload.size());
    const GuardVerdict v = to.guard.check(h, 0);
    if (v.kind != GuardVerdict::Accept && v.kind != GuardVerdict::Opened && v.kind != GuardVerdict::Unverified)
        return std::nullopt;
    ReceivedMessage rm;
    rm.message = Message{type, from.id, frame, payload, from.session};
    rm.verified = v.kind != GuardVerdict::Unverified;
    rm.opened = v.kind == GuardVerdict::Opened;
    rm.to_session = to_session;
    return rm;
}

std::optional<ReceivedMessage> deliver(Peer& from, Peer& to, const SessionSend& s) {
    return deliver(from, to, s.type, s.frame, s.payload, s.to_session);
}

std::vector<uint8_t> snapshot_payload(uint64_t frame, double sim_time_s = 0.0) {
    Snapshot s;
    s.frame = frame;
    s.sim_time_s = sim_time_s;
    return encode_snapshot(s);
}

const Clock::time_point t0 = Clock::time_point{} + 10000h;  // any instant: no clock is read

SlaveSessionConfig slave_config(int channel, uint32_t pid = 4242) {
    SlaveSessionConfig c;
    c.channel = channel;
    c.process_id = pid;
    c.idle_timeout = 30s;
    c.log_name = "slave c" + std::to_string(channel);
    return c;
}

MasterSession make_master(uint64_t session, std::vector<int> ids = {0}) {
    return MasterSession(ids, session, {100ms, 2000ms});
}

// One slave process for channel `channel`, joined to `master` (the three handshake steps, each
// checked); returns when the master counts it live.
struct Channel {
    Channel(int channel, uint64_t session, uint32_t pid = 4242)
        : peer(static_cast<uint16_t>(channel), session), session(slave_config(channel, pid), t0) {}
    Peer peer;
    SlaveSession session;
};

void join(Channel& ch, MasterSession& master, Peer& mpeer, Clock::time_point now) {
    const SlaveActions hello = ch.session.tick(now);
    ASSERT_EQ(hello.sends.size(), 1u);
    ASSERT_EQ(hello.sends[0].type, PacketType::Hello);
    ASSERT_EQ(hello.sends[0].to_session, 0u) << "a joining slave addresses whoever is master";
    auto at_master = deliver(ch.peer, mpeer, hello.sends[0]);
    ASSERT_TRUE(at_master);
    EXPECT_FALSE(at_master->verified);
    const MasterActions welcome = master.on_message(*at_master, now);
    ASSERT_EQ(welcome.sends.size(), 1u);
    ASSERT_EQ(welcome.sends[0].type, PacketType::Welcome);
    EXPECT_EQ(welcome.sends[0].to_session, ch.peer.session);
    EXPECT_TRUE(welcome.joined.empty()) << "a hello to session 0 proves nothing";
    auto at_slave = deliver(mpeer, ch.peer, welcome.sends[0]);
    ASSERT_TRUE(at_slave && at_slave->opened);
    ch.session.receive(*at_slave);
    const SlaveActions confirm = ch.session.step(now);
    ASSERT_EQ(confirm.sends.size(), 1u);
    ASSERT_EQ(confirm.sends[0].type, PacketType::Hello);
    EXPECT_EQ(confirm.sends[0].to_session, mpeer.session);
    EXPECT_EQ(ch.session.master_session(), mpeer.session);
    auto confirmed = deliver(ch.peer, mpeer, confirm.sends[0]);
    ASSERT_TRUE(confirmed && confirmed->opened);
    const MasterActions joined = master.on_message(*confirmed, now);
    ASSERT_EQ(joined.joined, std::vector<int>{ch.peer.id});
    ASSERT_EQ(joined.events.size(), 1u);
    EXPECT_EQ(joined.events[0]["event"], "channel_joined");
    EXPECT_EQ(master.barrier().state(ch.peer.id), ChannelState::Live);
}

// The slave handles a snapshot of the master's; returns what it did.
SlaveActions snapshot_to(Channel& ch, Peer& mpeer, uint64_t frame, Clock::time_point now,
                         const std::vector<uint8_t>& payload) {
    auto rm = deliver(mpeer, ch.peer, PacketType::Snapshot, frame, payload, 0);
    EXPECT_TRUE(rm);
    if (rm) ch.session.receive(*rm);
    return ch.session.step(now);
}

// Renders (trivially) and reports what a step handed out; returns the report's send.
SlaveSend render(Channel& ch, const SlaveActions& a) {
    EXPECT_TRUE(a.render);
    const SlaveActions done = ch.session.rendered(FrameReport{}, 0);
    EXPECT_EQ(done.sends.size(), 1u);
    return done.sends.empty() ? SlaveSend{} : done.sends[0];
}

}  // namespace

TEST(Sessions, HandshakeJoinsTheChannel) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Channel ch(0, 0xB1);
    join(ch, master, mpeer, t0);
    EXPECT_TRUE(master.all_live());
    EXPECT_EQ(master.counters().channel_joins, 1u);
    EXPECT_EQ(master.counters().welcomes_sent, 1u);
    EXPECT_EQ(master.counters().channel_restarts, 0u);
    EXPECT_EQ(ch.session.counters().master_sessions, 1u);
    EXPECT_EQ(ch.session.counters().hellos_sent, 2u);
}

TEST(Sessions, ReplayedHelloNeitherJoinsNorFloodsWelcomes) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Channel ch(0, 0xB1);
    join(ch, master, mpeer, t0);
    // The confirming hello (sequence 1) recorded and sent again: the guard drops it.
    HelloMessage h;
    h.channel = 0;
    h.process_id = 4242;
    EXPECT_FALSE(deliver(ch.peer, mpeer, PacketType::Hello, 0, encode_hello(h), mpeer.session, 1u));
    // A hello to session 0 again (a slow network): a welcome at most every 20 ms, never a join.
    auto again = deliver(ch.peer, mpeer, PacketType::Hello, 0, encode_hello(h), 0);
    ASSERT_TRUE(again);
    EXPECT_TRUE(master.on_message(*again, t0 + 10ms).sends.empty()) << "welcomed again within 20 ms";
    const MasterActions later = master.on_message(*again, t0 + 25ms);
    ASSERT_EQ(later.sends.size(), 1u);
    EXPECT_EQ(later.sends[0].type, PacketType::Welcome);
    EXPECT_TRUE(later.joined.empty());
    EXPECT_EQ(master.counters().channel_joins, 1u);
    EXPECT_EQ(master.counters().welcomes_sent, 2u);
    // The slave, already welcomed by this master, takes a repeated welcome as a reason to confirm.
    auto w = deliver(mpeer, ch.peer, later.sends[0]);
    ASSERT_TRUE(w && w->verified && !w->opened);
    ch.session.receive(*w);
    const SlaveActions a = ch.session.step(t0 + 200ms);
    ASSERT_EQ(a.sends.size(), 1u);
    EXPECT_EQ(a.sends[0].to_session, mpeer.session);
    EXPECT_EQ(ch.session.counters().master_sessions, 1u);
}

TEST(Sessions, RestartedMasterIsJoinedAgainAndResumes) {
    Peer old_peer(kMasterSender, 0xA1);
    MasterSession old_master = make_master(0xA1);
    Channel ch(0, 0xB1);
    join(ch, old_master, old_peer, t0);
    render(ch, snapshot_to(ch, old_peer, 5, t0 + 10ms, snapshot_payload(5)));
    EXPECT_EQ(ch.session.last_frame(), std::optional<uint64_t>(5));

    // A new master process: its packets are authentic but of a session the slave does not know.
    Peer new_peer(kMasterSender, 0xA2);
    MasterSession master = make_master(0xA2);
    auto quit = deliver(new_peer, ch.peer, PacketType::Quit, 0, {}, 0);
    ASSERT_TRUE(quit && !quit->verified);
    ch.session.receive(*quit);
    EXPECT_TRUE(ch.session.step(t0 + 20ms).sends.empty()) << "never acts on an unknown session";
    EXPECT_FALSE(ch.session.quitting());
    // So the next hello asks "whoever is master" for a welcome, naming the last frame rendered.
    const SlaveActions hello = ch.session.tick(t0 + 150ms);
    ASSERT_EQ(hello.sends.size(), 1u);
    EXPECT_EQ(hello.sends[0].to_session, 0u);
    const HelloMessage h = decode_hello(hello.sends[0].payload);
    EXPECT_TRUE(h.has_frame);
    EXPECT_EQ(h.last_frame, 5u);
    auto at_master = deliver(ch.peer, new_peer, hello.sends[0]);
    ASSERT_TRUE(at_master);
    const MasterActions welcome = master.on_message(*at_master, t0 + 150ms);
    ASSERT_EQ(welcome.sends.size(), 1u);
    auto w = deliver(new_peer, ch.peer, welcome.sends[0]);
    ASSERT_TRUE(w && w->opened);
    ch.session.receive(*w);
    const SlaveActions confirm = ch.session.step(t0 + 151ms);
    ASSERT_EQ(confirm.sends.size(), 1u);
    EXPECT_EQ(confirm.sends[0].to_session, new_peer.session);
    auto c = deliver(ch.peer, new_peer, confirm.sends[0]);
    ASSERT_TRUE(c && c->opened);
    EXPECT_EQ(master.on_message(*c, t0 + 152ms).joined, std::vector<int>{0});
    EXPECT_EQ(ch.session.counters().master_sessions, 2u);
    EXPECT_EQ(master.resume_after(), std::optional<uint64_t>(5));
    // The new master starts at frame 6; a frame the old one sent (5) with other content is
    // rendered again under the new session rather than ignored.
    const SlaveActions again = snapshot_to(ch, new_peer, 5, t0 + 200ms, snapshot_payload(5, 1.0));
    EXPECT_TRUE(again.render);
    EXPECT_EQ(ch.session.counters().rerendered, 1u);
}

TEST(Sessions, RestartedSlaveReplacesTheLiveChannel) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Channel first(0, 0xB1, 100);
    join(first, master, mpeer, t0);
    EXPECT_EQ(master.start_frame(0, snapshot_payload(0), t0 + 10ms, 0).sends.size(), 1u);
    // A new process for channel 0 (new nonce) joins while the old one is still live.
    Channel second(0, 0xB2, 200);
    const SlaveActions hello = second.session.tick(t0 + 20ms);
    auto at_master = deliver(second.peer, mpeer, hello.sends.at(0));
    ASSERT_TRUE(at_master);
    const MasterActions welcome = master.on_message(*at_master, t0 + 20ms);
    auto w = deliver(mpeer, second.peer, welcome.sends.at(0));
    ASSERT_TRUE(w && w->opened);
    second.session.receive(*w);
    auto c = deliver(second.peer, mpeer, second.session.step(t0 + 21ms).sends.at(0));
    ASSERT_TRUE(c && c->opened);
    const MasterActions joined = master.on_message(*c, t0 + 21ms);
    EXPECT_EQ(joined.joined, std::vector<int>{0});
    ASSERT_EQ(joined.events.size(), 1u);
    EXPECT_EQ(joined.events[0]["new_process"], true);
    EXPECT_EQ(joined.events[0]["pid"], 200);
    EXPECT_EQ(master.counters().channel_restarts, 1u);
    EXPECT_EQ(master.counters().channel_joins, 2u);
    // It renders the current frame: the snapshot goes out again at once.
    ASSERT_EQ(joined.sends.size(), 1u);
    EXPECT_EQ(joined.sends[0].type, PacketType::Snapshot);
    EXPECT_EQ(joined.sends[0].frame, 0u);
    EXPECT_EQ(master.counters().snapshot_resends, 1u);
    // The old process's packets are stale now.
    EXPECT_FALSE(deliver(first.peer, mpeer, PacketType::QuitAck, 0, {}, mpeer.session));
}

TEST(Sessions, QuitIsResentUntilAckedAndTheSlaveLingers) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Channel ch(0, 0xB1);
    join(ch, master, mpeer, t0);
    const MasterActions q1 = master.start_quit(7, t0 + 1s);
    ASSERT_EQ(q1.sends.size(), 1u);
    EXPECT_EQ(q1.sends[0].type, PacketType::Quit);
    EXPECT_EQ(q1.sends[0].frame, 8u);
    EXPECT_EQ(master.next_wake(), t0 + 1s + 50ms);
    EXPECT_TRUE(master.tick(t0 + 1s + 49ms).sends.empty());
    // The first quit was lost: the next round sends another.
    const MasterActions q2 = master.tick(t0 + 1s + 50ms);
    ASSERT_EQ(q2.sends.size(), 1u);
    auto at_slave = deliver(mpeer, ch.peer, q2.sends[0]);
    ASSERT_TRUE(at_slave);
    ch.session.receive(*at_slave);
    const SlaveActions ack = ch.session.step(t0 + 1s + 51ms);
    ASSERT_EQ(ack.sends.size(), 1u);
    EXPECT_EQ(ack.sends[0].type, PacketType::QuitAck);
    EXPECT_TRUE(ch.session.quitting());
    EXPECT_FALSE(ack.exit_code);
    // While lingering the slave acknowledges every quit, says no hello, and leaves after 300 ms.
    ch.session.receive(*deliver(mpeer, ch.peer, PacketType::Quit, 8, {}, 0));
    EXPECT_EQ(ch.session.step(t0 + 1s + 100ms).sends.size(), 1u);
    EXPECT_TRUE(ch.session.tick(t0 + 1s + 340ms).sends.empty());
    EXPECT_FALSE(ch.session.tick(t0 + 1s + 340ms).exit_code);
    EXPECT_EQ(ch.session.tick(t0 + 1s + 351ms).exit_code, std::optional<int>(0));
    // The master counts the acknowledgement once and is done at the end of the round.
    auto acked = deliver(ch.peer, mpeer, ack.sends[0]);
    ASSERT_TRUE(acked);
    master.on_message(*acked, t0 + 1s + 52ms);
    master.on_message(*acked, t0 + 1s + 53ms);
    EXPECT_EQ(master.counters().quit_acks, 1u);
    EXPECT_FALSE(master.quit_done());
    EXPECT_TRUE(master.tick(t0 + 1s + 100ms).sends.empty());
    EXPECT_TRUE(master.quit_done());
    EXPECT_TRUE(master.unconfirmed_quits().empty());
}

TEST(Sessions, UnconfirmedQuitEndsAfterTwoSeconds) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Channel ch(0, 0xB1);
    join(ch, master, mpeer, t0);
    int quits = static_cast<int>(master.start_quit(0, t0).sends.size());
    for (auto t = t0; !master.quit_done() && t < t0 + 5s; t += 10ms) quits += master.tick(t).sends.size();
    EXPECT_TRUE(master.quit_done());
    EXPECT_EQ(quits, 40);  // one per 50 ms round for 2 s
    EXPECT_EQ(master.unconfirmed_quits(), std::vector<int>{0});
}

TEST(Sessions, SilentChannelIsDroppedThenRejoins) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1, {0, 1});
    Channel a(0, 0xB1), b(1, 0xB2);
    join(a, master, mpeer, t0);
    join(b, master, mpeer, t0);
    const auto start = t0 + 1s;
    master.start_frame(3, snapshot_payload(3), start, 0);
    auto rep = render(a, snapshot_to(a, mpeer, 3, start, snapshot_payload(3)));
    master.on_message(*deliver(a.peer, mpeer, rep), start + 5ms);
    EXPECT_FALSE(master.frame_complete());
    // Resent every resend interval while channel 1 is silent ...
    EXPECT_EQ(master.tick(start + 99ms).sends.size(), 0u);
    EXPECT_EQ(master.tick(start + 100ms).sends.size(), 1u);
    EXPECT_EQ(master.counters().snapshot_resends, 1u);
    // ... and dropped after the channel timeout.
    const MasterActions drop = master.tick(start + 2000ms);
    EXPECT_EQ(drop.dropped, std::vector<int>{1});
    ASSERT_EQ(drop.events.size(), 1u);
    EXPECT_EQ(drop.events[0]["event"], "channel_dropped");
    EXPECT_EQ(drop.events[0]["frame"], 3);
    EXPECT_TRUE(master.frame_complete());
    EXPECT_EQ(master.counters().channel_drops, 1u);
    const auto reports = master.end_frame();
    EXPECT_EQ(reports.size(), 1u);
    EXPECT_TRUE(reports.count(0));
    // The next frame reaches it again (it was stalled, not gone): its report makes it live again.
    master.start_frame(4, snapshot_payload(4), start + 2100ms, 0);
    const SlaveSend back_rep = render(b, snapshot_to(b, mpeer, 4, start + 2100ms, snapshot_payload(4)));
    const MasterActions back = master.on_message(*deliver(b.peer, mpeer, back_rep), start + 2110ms);
    EXPECT_EQ(back.joined, std::vector<int>{1});
    ASSERT_EQ(back.events.size(), 1u);
    EXPECT_EQ(back.events[0]["event"], "channel_joined");
    EXPECT_EQ(master.barrier().state(1), ChannelState::Live);
    EXPECT_EQ(master.counters().channel_joins, 3u);
    EXPECT_FALSE(master.frame_complete()) << "channel 0 has not reported frame 4";
}

TEST(Sessions, CatchingUpRendersOnlyTheNewestSnapshot) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Channel ch(0, 0xB1);
    join(ch, master, mpeer, t0);
    render(ch, snapshot_to(ch, mpeer, 1, t0 + 10ms, snapshot_payload(1)));
    // A stall: frames 2, 3, 4 and a quit wait in the socket.
    for (uint64_t f = 2; f <= 4; ++f)
        ch.session.receive(*deliver(mpeer, ch.peer, PacketType::Snapshot, f, snapshot_payload(f), 0));
    ch.session.receive(*deliver(mpeer, ch.peer, PacketType::Quit, 5, {}, 0));
    const SlaveActions a = ch.session.step(t0 + 500ms);
    ASSERT_TRUE(a.render);
    EXPECT_EQ(a.render->snapshot.frame, 4u);
    EXPECT_EQ(ch.session.counters().skipped_snapshots, 2u);
    const SlaveSend rep = render(ch, a);
    EXPECT_EQ(decode_frame_report(rep.payload).frame, 4u);
    // The quit queued behind them is still handled, after the render.
    EXPECT_TRUE(ch.session.has_queued());
    EXPECT_EQ(ch.session.step(t0 + 501ms).sends.at(0).type, PacketType::QuitAck);
    EXPECT_EQ(ch.session.counters().frames_rendered, 2u);
}

TEST(Sessions, ResentSnapshotRepeatsTheReport) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Channel ch(0, 0xB1);
    join(ch, master, mpeer, t0);
    const auto payload = snapshot_payload(1, 2.5);
    const SlaveActions a = snapshot_to(ch, mpeer, 1, t0 + 10ms, payload);
    ASSERT_TRUE(a.render);
    FrameReport r;
    r.render_ms = 12.5f;
    const SlaveSend first = ch.session.rendered(r, 7).sends.at(0);
    const FrameReport sent = decode_frame_report(first.payload);
    EXPECT_EQ(sent.snapshot_hash, snapshot_hash(payload));
    EXPECT_EQ(sent.packets_rejected, 7u);
    EXPECT_FLOAT_EQ(sent.render_ms, 12.5f);
    // The report was lost; the master resends the snapshot: the same report again, no render.
    const SlaveActions again = snapshot_to(ch, mpeer, 1, t0 + 110ms, payload);
    EXPECT_FALSE(again.render);
    ASSERT_EQ(again.sends.size(), 1u);
    EXPECT_EQ(again.sends[0].type, PacketType::FrameDone);
    EXPECT_EQ(again.sends[0].payload, first.payload);
    EXPECT_EQ(ch.session.counters().resent_snapshots, 1u);
    EXPECT_EQ(ch.session.counters().frames_rendered, 1u);
    // The same frame with other content from the same master cannot be: ignored.
    EXPECT_FALSE(snapshot_to(ch, mpeer, 1, t0 + 120ms, snapshot_payload(1, 9.0)).render);
    EXPECT_EQ(ch.session.counters().late_snapshots, 1u);
}

TEST(Sessions, LateOrReorderedSnapshotIsIgnored) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Channel ch(0, 0xB1);
    join(ch, master, mpeer, t0);
    render(ch, snapshot_to(ch, mpeer, 3, t0 + 10ms, snapshot_payload(3)));
    const SlaveActions old = snapshot_to(ch, mpeer, 2, t0 + 20ms, snapshot_payload(2));
    EXPECT_FALSE(old.render);
    EXPECT_TRUE(old.sends.empty());
    EXPECT_EQ(ch.session.counters().late_snapshots, 1u);
    // Frames never seen are counted as missed when a later one arrives.
    const SlaveActions jump = snapshot_to(ch, mpeer, 6, t0 + 30ms, snapshot_payload(6));
    ASSERT_TRUE(jump.render);
    EXPECT_EQ(ch.session.counters().missed_frames, 2u);
    // A snapshot whose header names another frame than its body is malformed.
    EXPECT_FALSE(snapshot_to(ch, mpeer, 9, t0 + 40ms, snapshot_payload(8)).render);
    EXPECT_EQ(ch.session.counters().malformed_snapshots, 1u);
}

TEST(Sessions, MalformedReportIsCounted) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1, {0, 1});
    Channel ch(0, 0xB1);
    join(ch, master, mpeer, t0);
    master.start_frame(0, snapshot_payload(0), t0 + 1s, 0);
    master.on_message(*deliver(ch.peer, mpeer, PacketType::FrameDone, 0, {1, 2, 3}, mpeer.session), t0 + 1s);
    EXPECT_EQ(master.counters().malformed_messages, 1u);
    FrameReport other;
    other.channel = 1;  // channel 0 reporting for channel 1
    other.snapshot_hash = "0123456789abcdef";
    master.on_message(*deliver(ch.peer, mpeer, PacketType::FrameDone, 0, encode_frame_report(other), mpeer.session),
                      t0 + 1s);
    EXPECT_EQ(master.counters().malformed_messages, 2u);
    EXPECT_FALSE(master.frame_complete());
    // A report for another frame is late, not malformed; a good one completes the frame.
    FrameReport late;
    late.channel = 0;
    late.frame = 5;
    late.snapshot_hash = "0123456789abcdef";
    master.on_message(*deliver(ch.peer, mpeer, PacketType::FrameDone, 5, encode_frame_report(late), mpeer.session),
                      t0 + 1s);
    EXPECT_EQ(master.counters().late_reports, 1u);
    late.frame = 0;
    master.on_message(*deliver(ch.peer, mpeer, PacketType::FrameDone, 0, encode_frame_report(late), mpeer.session),
                      t0 + 1s);
    EXPECT_TRUE(master.frame_complete());
    EXPECT_EQ(master.counters().malformed_messages, 2u);
}

TEST(Sessions, UnknownChannelAndUnverifiedMessagesAreNotActedOn) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    Peer stranger(9, 0xC9);
    HelloMessage h;
    h.channel = 9;
    const MasterActions a = master.on_message(*deliver(stranger, mpeer, PacketType::Hello, 0, encode_hello(h), 0), t0);
    EXPECT_TRUE(a.sends.empty());
    EXPECT_EQ(master.counters().unknown_channel, 1u);
    // A hello that names another channel than its sender is malformed.
    Channel ch(0, 0xB1);
    h.channel = 1;
    master.on_message(*deliver(ch.peer, mpeer, PacketType::Hello, 0, encode_hello(h), 0), t0);
    EXPECT_EQ(master.counters().malformed_messages, 1u);
    EXPECT_EQ(master.counters().welcomes_sent, 0u);
}

TEST(Sessions, SlaveGivesUpWhenNoSnapshotArrives) {
    SlaveSessionConfig c = slave_config(0);
    c.idle_timeout = 2s;
    SlaveSession s(c, t0);
    EXPECT_FALSE(s.tick(t0 + 1s).exit_code);
    EXPECT_EQ(s.tick(t0 + 2001ms).exit_code, std::optional<int>(3));
    // Hellos while joining: every 100 ms, not more often.
    SlaveSession j(c, t0);
    EXPECT_EQ(j.tick(t0).sends.size(), 1u);
    EXPECT_TRUE(j.tick(t0 + 100ms).sends.empty());
    EXPECT_EQ(j.tick(t0 + 101ms).sends.size(), 1u);
    EXPECT_EQ(j.counters().hellos_sent, 2u);
}

// The swap lock (docs/SWAP_LOCK.md): "ready N" is the report, "present N" the master's answer.
namespace {

MasterSession make_locked_master(uint64_t session, std::vector<int> ids) {
    return MasterSession(ids, session, {100ms, 2000ms, true});
}

SlaveSend render_ready(Channel& ch, const SlaveActions& a, uint64_t ready_ns) {
    EXPECT_TRUE(a.render);
    FrameReport r;
    r.presentation = PresentTiming{ready_ns};
    const SlaveActions done = ch.session.rendered(r, 0);
    EXPECT_FALSE(done.present) << "a frame is held until its present";
    EXPECT_EQ(done.sends.size(), 1u);
    return done.sends.empty() ? SlaveSend{} : done.sends[0];
}

std::vector<MasterSend> presents(const MasterActions& a) {
    std::vector<MasterSend> out;
    for (const auto& s : a.sends)
        if (s.type == PacketType::Present) out.push_back(s);
    return out;
}

SlaveActions deliver_to(Channel& ch, Peer& mpeer, const MasterSend& s, Clock::time_point now) {
    auto rm = deliver(mpeer, ch.peer, s);
    EXPECT_TRUE(rm);
    if (rm) ch.session.receive(*rm);
    return ch.session.step(now);
}

}  // namespace

TEST(Sessions, PresentGoesOutExactlyWhenEveryLiveChannelIsReady) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_locked_master(0xA1, {0, 1});
    Channel a(0, 0xB1), b(1, 0xB2);
    join(a, master, mpeer, t0);
    join(b, master, mpeer, t0);
    const auto start = t0 + 1s;
    EXPECT_TRUE(presents(master.start_frame(3, snapshot_payload(3), start, 0)).empty());
    const SlaveSend ra = render_ready(a, snapshot_to(a, mpeer, 3, start, snapshot_payload(3)), 111);
    const SlaveSend rb = render_ready(b, snapshot_to(b, mpeer, 3, start, snapshot_payload(3)), 222);
    EXPECT_EQ(a.session.held_frame(), std::optional<uint64_t>(3));
    EXPECT_TRUE(presents(master.on_message(*deliver(a.peer, mpeer, ra), start + 5ms)).empty())
        << "channel 1 is not ready yet";
    EXPECT_TRUE(presents(master.tick(start + 6ms)).empty());
    const MasterActions all = master.on_message(*deliver(b.peer, mpeer, rb), start + 7ms);
    const auto p = presents(all);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].frame, 3u);
    EXPECT_EQ(decode_present(p[0].payload).frame, 3u);
    EXPECT_EQ(p[0].to_session, 0u);
    EXPECT_TRUE(master.frame_complete());
    EXPECT_EQ(master.counters().presents_sent, 1u);
    // Each slave shows its held frame on it; the next report says when.
    const SlaveActions shown = deliver_to(a, mpeer, p[0], start + 8ms);
    ASSERT_TRUE(shown.present);
    EXPECT_EQ(shown.present->frame, 3u);
    EXPECT_EQ(shown.present->ready_ns, 111u);
    EXPECT_EQ(shown.present->cause, PresentCause::Present);
    EXPECT_FALSE(a.session.held_frame());
    a.session.presented(3, 5000);
    const auto reports = master.end_frame();
    ASSERT_EQ(reports.size(), 2u);
    EXPECT_EQ(reports.at(1).presentation->ready_ns, 222u);
    master.start_frame(4, snapshot_payload(4), start + 20ms, 0);
    const FrameReport next =
        decode_frame_report(render_ready(a, snapshot_to(a, mpeer, 4, start + 20ms, snapshot_payload(4)), 333).payload);
    ASSERT_TRUE(next.presentation);
    EXPECT_EQ(next.presentation->ready_ns, 333u);
    EXPECT_TRUE(next.presentation->has_present);
    EXPECT_EQ(next.presentation->presented_frame, 3u);
    EXPECT_EQ(next.presentation->present_ns, 5000u);
    EXPECT_EQ(a.session.counters().frames_presented, 1u);
}

TEST(Sessions, LostPresentIsResentAndRecoveredByTheNextSnapshot) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_locked_master(0xA1, {0});
    Channel a(0, 0xB1);
    join(a, master, mpeer, t0);
    const auto start = t0 + 1s;
    master.start_frame(3, snapshot_payload(3), start, 0);
    const auto p = presents(master.on_message(
        *deliver(a.peer, mpeer, render_ready(a, snapshot_to(a, mpeer, 3, start, snapshot_payload(3)), 1)),
        start + 5ms));
    ASSERT_EQ(p.size(), 1u);  // ... and lost
    master.end_frame();
    // Resent every resend interval until the next frame starts.
    EXPECT_EQ(master.next_wake(), start + 105ms);
    EXPECT_TRUE(presents(master.tick(start + 104ms)).empty());
    EXPECT_EQ(presents(master.tick(start + 105ms)).size(), 1u);
    EXPECT_EQ(master.counters().present_resends, 1u);
    // That one is lost too; the next snapshot implies it: shown first, then the render.
    const MasterActions next = master.start_frame(4, snapshot_payload(4), start + 150ms, 0);
    EXPECT_TRUE(presents(next).empty());
    EXPECT_TRUE(presents(master.tick(start + 250ms)).empty()) << "no present of frame 3 once frame 4 started";
    const SlaveActions s = snapshot_to(a, mpeer, 4, start + 150ms, snapshot_payload(4));
    ASSERT_TRUE(s.present);
    EXPECT_EQ(s.present->frame, 3u);
    EXPECT_EQ(s.present->cause, PresentCause::Implied);
    ASSERT_TRUE(s.render);
    EXPECT_EQ(s.render->snapshot.frame, 4u);
    EXPECT_EQ(a.session.counters().presents_implied, 1u);
    // A later present implies the held frame too (the master went on without us).
    render_ready(a, s, 2);
    const SlaveActions later = deliver_to(a, mpeer, {PacketType::Present, 6, encode_present({6}), 0}, start + 300ms);
    ASSERT_TRUE(later.present);
    EXPECT_EQ(later.present->frame, 4u);
    EXPECT_EQ(later.present->cause, PresentCause::Implied);
    // So does the quit, before it is acknowledged.
    render_ready(a, snapshot_to(a, mpeer, 7, start + 400ms, snapshot_payload(7)), 3);
    const SlaveActions quit = deliver_to(a, mpeer, {PacketType::Quit, 8, {}, 0}, start + 500ms);
    ASSERT_TRUE(quit.present);
    EXPECT_EQ(quit.present->frame, 7u);
    EXPECT_EQ(quit.sends.at(0).type, PacketType::QuitAck);
}

TEST(Sessions, LateRepeatedReplayedOrMalformedPresentIsIgnored) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_locked_master(0xA1, {0});
    Channel a(0, 0xB1);
    join(a, master, mpeer, t0);
    const auto start = t0 + 1s;
    render_ready(a, snapshot_to(a, mpeer, 3, start, snapshot_payload(3)), 1);
    // Before its frame is held, a present of an older frame shows nothing.
    EXPECT_FALSE(deliver_to(a, mpeer, {PacketType::Present, 2, encode_present({2}), 0}, start + 1ms).present);
    // One whose body names another frame than its header is malformed.
    EXPECT_FALSE(deliver_to(a, mpeer, {PacketType::Present, 3, encode_present({4}), 0}, start + 2ms).present);
    EXPECT_FALSE(deliver_to(a, mpeer, {PacketType::Present, 3, {1, 2}, 0}, start + 2ms).present);
    EXPECT_EQ(a.session.counters().stale_presents, 3u);
    EXPECT_EQ(a.session.held_frame(), std::optional<uint64_t>(3));
    const uint32_t seq = mpeer.sequence;
    ASSERT_TRUE(deliver_to(a, mpeer, {PacketType::Present, 3, encode_present({3}), 0}, start + 3ms).present);
    a.session.presented(3, 10);
    // The master's resend (a new datagram) and a replay of the one that showed it: nothing twice.
    EXPECT_FALSE(deliver_to(a, mpeer, {PacketType::Present, 3, encode_present({3}), 0}, start + 100ms).present);
    EXPECT_FALSE(deliver(mpeer, a.peer, PacketType::Present, 3, encode_present({3}), 0, seq))
        << "the guard drops a replayed present";
    EXPECT_EQ(a.session.counters().stale_presents, 4u);
    EXPECT_EQ(a.session.counters().frames_presented, 1u);
    // The resent snapshot of the frame shown repeats its report and shows nothing.
    const SlaveActions again = snapshot_to(a, mpeer, 3, start + 200ms, snapshot_payload(3));
    EXPECT_FALSE(again.present);
    EXPECT_FALSE(again.render);
    EXPECT_EQ(again.sends.size(), 1u);
}

TEST(Sessions, DroppedChannelReleasesThePresent) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_locked_master(0xA1, {0, 1});
    Channel a(0, 0xB1), b(1, 0xB2);
    join(a, master, mpeer, t0);
    join(b, master, mpeer, t0);
    const auto start = t0 + 1s;
    master.start_frame(3, snapshot_payload(3), start, 0);
    const SlaveSend ra = render_ready(a, snapshot_to(a, mpeer, 3, start, snapshot_payload(3)), 1);
    EXPECT_TRUE(presents(master.on_message(*deliver(a.peer, mpeer, ra), start + 5ms)).empty());
    EXPECT_TRUE(presents(master.tick(start + 1999ms)).empty()) << "channel 1 is still expected";
    const MasterActions drop = master.tick(start + 2000ms);
    EXPECT_EQ(drop.dropped, std::vector<int>{1});
    const auto p = presents(drop);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].frame, 3u);
    EXPECT_TRUE(deliver_to(a, mpeer, p[0], start + 2001ms).present);
}

TEST(Sessions, WithoutTheSwapLockAFrameIsShownAtOnceAndNoPresentIsSent) {
    Peer mpeer(kMasterSender, 0xA1);
    MasterSession master = make_master(0xA1);
    SlaveSessionConfig c = slave_config(0);
    c.swap_lock = false;
    Channel a(0, 0xB1);
    a.session = SlaveSession(c, t0);
    join(a, master, mpeer, t0);
    const auto start = t0 + 1s;
    master.start_frame(3, snapshot_payload(3), start, 0);
    ASSERT_TRUE(snapshot_to(a, mpeer, 3, start, snapshot_payload(3)).render);
    FrameReport r;
    r.presentation = PresentTiming{77};
    const SlaveActions done = a.session.rendered(r, 0);
    ASSERT_TRUE(done.present);
    EXPECT_EQ(done.present->cause, PresentCause::Unlocked);
    EXPECT_EQ(done.present->ready_ns, 77u);
    const MasterActions rep = master.on_message(*deliver(a.peer, mpeer, done.sends.at(0)), start + 5ms);
    EXPECT_TRUE(master.frame_complete());
    EXPECT_TRUE(presents(rep).empty());
    EXPECT_TRUE(presents(master.tick(start + 500ms)).empty());
    EXPECT_EQ(master.counters().presents_sent, 0u);
}

// Replay protection and restarts: the sequence window of one sender session and the session
// guard's handshake, without sockets (the cluster tests run them over real networks).
#include <gtest/gtest.h>

#include "wire/packet.hpp"
#include "wire/session_guard.hpp"
#include "wire/sequence_window.hpp"

using namespace cupola;
using V = SequenceWindow::Verdict;

namespace {
constexpr uint64_t kMs = 1'000'000;
}

TEST(SequenceWindow, FreshReorderedDuplicateAndReplay) {
    SequenceWindow w(500 * kMs);
    EXPECT_EQ(w.check(10, 1 * kMs), V::Fresh);
    EXPECT_EQ(w.check(12, 2 * kMs), V::Fresh);
    EXPECT_EQ(w.check(11, 3 * kMs), V::Reordered);  // late but never seen
    EXPECT_EQ(w.check(11, 4 * kMs), V::Duplicate);  // the network sent it twice
    for (uint32_t s = 13; s < 13 + SequenceWindow::kDuplicateArrivals; ++s) EXPECT_EQ(w.check(s, 5 * kMs), V::Fresh);
    EXPECT_EQ(w.check(12, 900 * kMs), V::Replayed);  // the same datagram long after, many datagrams later
    EXPECT_EQ(w.check(9, 901 * kMs), V::Reordered);  // older than the first, still in the window
    EXPECT_EQ(w.check(100, 902 * kMs), V::Fresh);
}

// A receiver busy rendering reads the network's copy long after the first: it is still a
// duplicate, since almost nothing of its sender came between the two.
TEST(SequenceWindow, ARepeatReadLateButRightAfterItsFirstCopyIsADuplicate) {
    SequenceWindow w(500 * kMs);
    EXPECT_EQ(w.check(1, 0), V::Fresh);
    EXPECT_EQ(w.check(2, 0), V::Fresh);
    for (uint32_t s = 3; s < 3 + SequenceWindow::kDuplicateArrivals - 1; ++s) EXPECT_EQ(w.check(s, 1 * kMs), V::Fresh);
    EXPECT_EQ(w.check(2, 2000 * kMs), V::Duplicate);  // kDuplicateArrivals - 1 between
    EXPECT_EQ(w.check(1, 2000 * kMs), V::Replayed);   // kDuplicateArrivals + 1 between
}

// One copy stamped by the kernel at its arrival, the other at the read when the kernel had not
// turned its stamps on yet: the second copy may look older than the first. Never a replay.
TEST(SequenceWindow, ARepeatThatLooksOlderThanItsFirstCopyIsADuplicate) {
    SequenceWindow w(500 * kMs);
    EXPECT_EQ(w.check(1, 900 * kMs), V::Fresh);
    for (uint32_t s = 2; s < 2 + 2 * SequenceWindow::kDuplicateArrivals; ++s)
        EXPECT_EQ(w.check(s, 901 * kMs), V::Fresh);
    EXPECT_EQ(w.check(1, 899 * kMs), V::Duplicate);
    EXPECT_EQ(w.check(2, 2000 * kMs), V::Replayed);
}

TEST(SequenceWindow, OlderThanTheWindowIsAReplay) {
    SequenceWindow w;
    EXPECT_EQ(w.check(5000, 0), V::Fresh);
    EXPECT_EQ(w.check(5000 - SequenceWindow::kSize, 1), V::Replayed);
    EXPECT_EQ(w.check(5000 - SequenceWindow::kSize + 1, 1), V::Reordered);
    // A jump forward forgets what slid out of the window: the slots are reused correctly.
    EXPECT_EQ(w.check(5000 + 3 * SequenceWindow::kSize, 2), V::Fresh);
    EXPECT_EQ(w.check(5000 + 3 * SequenceWindow::kSize - 1, 3), V::Reordered);
    EXPECT_EQ(w.check(5000 + 2 * SequenceWindow::kSize + 1, 3), V::Reordered);
    EXPECT_EQ(w.check(5000 + 2 * SequenceWindow::kSize, 3), V::Replayed);
}

TEST(SequenceWindow, WorksAcrossTheCounterWrap) {
    SequenceWindow w;
    EXPECT_EQ(w.check(0xFFFFFFFEu, 0), V::Fresh);
    EXPECT_EQ(w.check(0xFFFFFFFFu, 0), V::Fresh);
    EXPECT_EQ(w.check(1u, 0), V::Fresh);
    EXPECT_EQ(w.check(0u, 0), V::Reordered);
    EXPECT_EQ(w.check(0xFFFFFFFFu, 0), V::Duplicate);
}

namespace {

PacketHeader header(PacketType type, uint16_t sender, uint64_t session, uint32_t seq, uint64_t to = 0) {
    PacketHeader h;
    h.type = type;
    h.sender = sender;
    h.session = session;
    h.sequence = seq;
    h.to_session = to;
    return h;
}

// The slave's policy, as net/wire_endpoint.cpp gives it.
SessionGuard slave_guard(uint64_t self) {
    return SessionGuard(self, [self](const PacketHeader& h) {
        if (h.sender != kMasterSender) return SessionOpen::Ignore;
        if (h.type == PacketType::Welcome && h.to_session == self) return SessionOpen::Open;
        return SessionOpen::Unverified;
    });
}

}  // namespace

TEST(SessionGuard, ASlaveTrustsAMasterSessionOnlyAfterItsWelcome) {
    const uint64_t slave = 0x5151, m1 = 0xA1, m2 = 0xA2;
    SessionGuard g = slave_guard(slave);
    // Snapshots of a master we have not been welcomed by are unverified: never rendered.
    EXPECT_EQ(g.check(header(PacketType::Snapshot, kMasterSender, m1, 0), 0).kind, GuardVerdict::Unverified);
    // A welcome for another slave process is normal traffic, ignored.
    EXPECT_EQ(g.check(header(PacketType::Welcome, kMasterSender, m1, 1, 0x7777), 0).kind, GuardVerdict::Ignored);
    // Ours opens the session; then the master's packets are accepted in sequence.
    EXPECT_EQ(g.check(header(PacketType::Welcome, kMasterSender, m1, 2, slave), 0).kind, GuardVerdict::Opened);
    EXPECT_EQ(g.peer_session(kMasterSender), m1);
    EXPECT_EQ(g.check(header(PacketType::Snapshot, kMasterSender, m1, 3), 0).kind, GuardVerdict::Accept);
    EXPECT_EQ(g.check(header(PacketType::Snapshot, kMasterSender, m1, 3), 1).kind, GuardVerdict::Duplicate);
    for (uint32_t s = 4; s < 4 + SequenceWindow::kDuplicateArrivals; ++s)
        EXPECT_EQ(g.check(header(PacketType::Snapshot, kMasterSender, m1, s), 2 * kMs).kind, GuardVerdict::Accept);
    EXPECT_EQ(g.check(header(PacketType::Snapshot, kMasterSender, m1, 3), 900 * kMs).reason, RejectReason::Replayed);

    // The master restarts (m2) and welcomes us: m1 is over, its packets are stale from now on.
    EXPECT_EQ(g.check(header(PacketType::Snapshot, kMasterSender, m2, 0), 0).kind, GuardVerdict::Unverified);
    EXPECT_EQ(g.check(header(PacketType::Welcome, kMasterSender, m2, 1, slave), 0).kind, GuardVerdict::Opened);
    const GuardVerdict old = g.check(header(PacketType::Snapshot, kMasterSender, m1, 40), 0);
    EXPECT_EQ(old.kind, GuardVerdict::Rejected);
    EXPECT_EQ(old.reason, RejectReason::StaleSession);
    // A replayed welcome of the old session cannot bring it back.
    EXPECT_EQ(g.check(header(PacketType::Welcome, kMasterSender, m1, 2, slave), 0).reason, RejectReason::StaleSession);
    EXPECT_EQ(g.peer_session(kMasterSender), m2);
}

TEST(SessionGuard, PacketsAddressedToAnEarlierSessionOfOursAreStale) {
    SessionGuard g(0xB2, [](const PacketHeader& h) {
        return h.type == PacketType::Hello && h.to_session == 0xB2 ? SessionOpen::Open : SessionOpen::Unverified;
    });
    // A report to the master session 0xB1 (before this master restarted).
    const GuardVerdict v = g.check(header(PacketType::FrameDone, 3, 0x33, 10, 0xB1), 0);
    EXPECT_EQ(v.kind, GuardVerdict::Rejected);
    EXPECT_EQ(v.reason, RejectReason::StaleSession);
    // A hello to nobody in particular is passed up (to be welcomed), not trusted.
    EXPECT_EQ(g.check(header(PacketType::Hello, 3, 0x33, 11, 0), 0).kind, GuardVerdict::Unverified);
    EXPECT_EQ(g.peer_session(3), 0u);
    // Once it confirms our session it is trusted; a new process of the channel replaces it.
    EXPECT_EQ(g.check(header(PacketType::Hello, 3, 0x33, 12, 0xB2), 0).kind, GuardVerdict::Opened);
    EXPECT_EQ(g.check(header(PacketType::Hello, 3, 0x34, 0, 0xB2), 0).kind, GuardVerdict::Opened);
    EXPECT_EQ(g.check(header(PacketType::FrameDone, 3, 0x33, 13, 0xB2), 0).reason, RejectReason::StaleSession);
    // Session 0 is never valid.
    EXPECT_EQ(g.check(header(PacketType::Hello, 4, 0, 0, 0xB2), 0).reason, RejectReason::UnknownSession);
}

TEST(SessionGuard, ReorderedDatagramsAreAcceptedAndFlagged) {
    SessionGuard g = slave_guard(1);
    ASSERT_EQ(g.check(header(PacketType::Welcome, kMasterSender, 9, 100, 1), 0).kind, GuardVerdict::Opened);
    EXPECT_FALSE(g.check(header(PacketType::Snapshot, kMasterSender, 9, 102), 0).reordered);
    const GuardVerdict late = g.check(header(PacketType::Snapshot, kMasterSender, 9, 101), 0);
    EXPECT_EQ(late.kind, GuardVerdict::Accept);
    EXPECT_TRUE(late.reordered);
}

// cupola-fuzz-wire-corpus DIR: writes the seed inputs of cupola-fuzz-wire into DIR, in the input
// format of fuzz_wire_format.hpp: authentic datagrams (snapshot, hello, frame report, quit, one
// fragment of a fragmented snapshot), reassembly scripts (in order, shuffled with a duplicate,
// tampered, eviction with few pending slots, several message kinds) and valid message payloads.
// The datagrams come from PacketCodec::encode, so the seeds follow whatever header layout the
// sources define; fuzz/corpus/wire holds one generated set (regenerate it after a protocol
// change: build/bin/cupola-fuzz-wire-corpus fuzz/corpus/wire), and the bounded ctest adds a
// freshly generated set to its scratch copy of those.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz_wire_format.hpp"
#include "wire/packet.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;
using namespace cupola::fuzz;

namespace {

Snapshot sample_snapshot(size_t bodies, size_t glare) {
    Snapshot s;
    s.frame = 4242;
    s.sim_time_s = 765432101.125;
    s.camera_position_m = {1.4959787e11, -3.0e7, 1.0e-3};
    s.camera_orientation = glm::normalize(glm::dquat(0.9, 0.1, -0.3, 0.2));
    for (size_t i = 0; i < bodies; ++i) {
        BodyState b;
        b.id = static_cast<uint16_t>(i);
        b.position_m = {1e11 + i * 1234.5, -2e10 / (i + 1.0), 7.0 * i};
        b.orientation = glm::normalize(glm::dquat(1.0, 0.01 * i, 0.02, -0.03 * i));
        s.bodies.push_back(b);
    }
    s.settings.exposure = 2.5f;
    s.settings.flags = with_alignment_pattern(3, AlignmentPattern::Grid);  // shadow mode and grid pattern
    s.settings.glare_phase = 1.25f;
    for (size_t i = 0; i < glare; ++i) {
        GlareSource g;
        g.body = i == 0 ? 0 : GlareSource::kCatalogStar;
        g.star = static_cast<uint32_t>(i * 17);
        g.direction = glm::normalize(glm::vec3(0.3f, -0.4f + 0.1f * i, 0.8f));
        g.angular_radius = i == 0 ? 4.65e-3f : 0.0f;
        g.irradiance = {3.9f, 3.8f, 3.5f};
        g.visible_fraction = 0.5f;
        g.centroid_offset = {1e-3f, -2e-4f, 0.0f};
        g.origin = i == 0 ? GlareOrigin::Measured : GlareOrigin::Analytic;
        g.measured_frame = i == 0 ? s.frame - 1 : 0;
        s.glare.push_back(g);
    }
    return s;
}

FrameReport sample_report(size_t glare) {
    FrameReport r;
    r.channel = 2;
    r.frame = 4242;
    r.snapshot_hash = "0123456789abcdef";
    r.render_ms = 4.5f;
    r.write_ms = 1.25f;
    r.packets_rejected = 3;
    r.snapshots_missed = 1;
    r.snapshot_received_ns = 123456789;
    r.presentation = PresentTiming{123457000, true, 4241, 123400000};
    for (size_t i = 0; i < glare; ++i) {
        GlareMeasurement g;
        g.body = static_cast<uint16_t>(i);
        g.frame = 4241;
        g.total_sr = 1e-4f;
        for (float& v : g.visible_sr) v = 1e-6f * (i + 1);
        r.glare.push_back(g);
    }
    return r;
}

const PacketCodec& codec() {
    static const PacketCodec c(kClusterId, harness_key());
    return c;
}

std::vector<std::vector<uint8_t>> encode(PacketType type, uint16_t sender, uint64_t frame,
                                         const std::vector<uint8_t>& message, size_t max_datagram) {
    uint32_t seq = 1;
    return codec().encode(type, sender, frame, message, max_datagram, &seq);
}

// max_datagram_sel for a wanted max_datagram (see Op::Encode).
uint16_t datagram_sel(size_t max_datagram) {
    return static_cast<uint16_t>(max_datagram - (kHeaderSize + kTagSize + 16));
}

void op_encode(Writer& w, PacketType type, uint16_t sender, uint16_t frame, size_t max_datagram, uint8_t flags,
               const std::vector<uint8_t>& literal, uint16_t pad = 0) {
    w.u8(static_cast<uint8_t>(Op::Encode));
    w.u8(static_cast<uint8_t>(type));
    w.u16(sender);
    w.u16(frame);
    w.u32(100);
    w.u16(datagram_sel(max_datagram));
    w.u8(flags);
    w.u16(static_cast<uint16_t>(literal.size()));
    w.bytes(literal);
    w.u16(pad);
}
void op_deliver(Writer& w, uint16_t index) {
    w.u8(static_cast<uint8_t>(Op::Deliver));
    w.u16(index);
}
struct EditSpec {
    Edit kind;
    uint16_t pos;
    uint8_t value;
};
void op_tamper(Writer& w, uint16_t index, bool keep, const std::vector<EditSpec>& edits) {
    w.u8(static_cast<uint8_t>(Op::Tamper));
    w.u16(index);
    w.u8(keep ? kTamperKeep : 0);
    w.u8(static_cast<uint8_t>(edits.size() - 1));
    for (const auto& e : edits) {
        w.u8(static_cast<uint8_t>(e.kind));
        w.u16(e.pos);
        w.u8(e.value);
    }
}

Writer start(Mode m) {
    Writer w;
    w.u8(static_cast<uint8_t>(m));
    return w;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    int written = 0;
    auto save = [&](const std::string& name, const Writer& w) {
        std::ofstream out(dir / name, std::ios::binary);
        out.write(reinterpret_cast<const char*>(w.out.data()), static_cast<std::streamsize>(w.out.size()));
        if (!out) {
            std::fprintf(stderr, "cannot write %s\n", (dir / name).c_str());
            std::exit(1);
        }
        ++written;
    };

    const std::vector<uint8_t> snap = encode_snapshot(sample_snapshot(3, 2));
    const std::vector<uint8_t> snap_small = encode_snapshot(sample_snapshot(0, 0));
    HelloMessage hello_msg;
    hello_msg.channel = 2;
    hello_msg.process_id = 31337;
    hello_msg.last_frame = 4241;
    const std::vector<uint8_t> hello = encode_hello(hello_msg);
    const std::vector<uint8_t> report = encode_frame_report(sample_report(2));
    const size_t frag3 = kHeaderSize + kTagSize + (snap.size() + 2) / 3;  // three fragments

    // Single datagrams, as received and re-signed.
    {
        Writer w = start(Mode::Raw);
        w.bytes(encode(PacketType::Snapshot, kMasterSender, 4242, snap, 1400)[0]);
        save("raw-snapshot", w);
    }
    {
        Writer w = start(Mode::Raw);
        w.bytes(encode(PacketType::Snapshot, kMasterSender, 4242, snap, frag3)[1]);
        save("raw-snapshot-fragment", w);
    }
    {
        Writer w = start(Mode::Raw);
        w.bytes(encode(PacketType::Hello, 2, 0, hello, 1400)[0]);
        save("raw-hello", w);
    }
    {
        Writer w = start(Mode::Raw);
        w.bytes(encode(PacketType::FrameDone, 2, 4242, report, 1400)[0]);
        save("raw-frame-done", w);
    }
    {
        Writer w = start(Mode::Raw);
        w.bytes(encode(PacketType::Quit, kMasterSender, 4243, {}, 1400)[0]);
        save("raw-quit", w);
    }
    {
        Writer w = start(Mode::RawSigned);
        w.bytes(encode(PacketType::Snapshot, kMasterSender, 4242, snap, frag3)[2]);
        save("signed-snapshot-fragment", w);
    }
    {
        Writer w = start(Mode::RawSigned);
        w.bytes(encode(PacketType::FrameDone, 1, 4242, report, 1400)[0]);
        save("signed-frame-done", w);
    }

    // Reassembly scripts.
    {
        Writer w = start(Mode::Reassembly);
        w.u8(7);  // 8 pending
        op_encode(w, PacketType::Snapshot, kMasterSender, 4242, frag3, kEncodeDeliverNow, snap);
        save("reasm-in-order", w);
    }
    {
        Writer w = start(Mode::Reassembly);
        w.u8(7);
        op_encode(w, PacketType::Snapshot, kMasterSender, 4242, frag3, 0, snap);
        for (uint16_t i : {2, 0, 0, 1}) op_deliver(w, i);
        save("reasm-shuffled-duplicate", w);
    }
    {
        Writer w = start(Mode::Reassembly);
        w.u8(7);
        op_encode(w, PacketType::Snapshot, kMasterSender, 4242, frag3, 0, snap);
        op_deliver(w, 0);
        op_tamper(w, 1, true, {{Edit::Xor, 16, 0x01}, {Edit::Set, 50, 0xFF}});
        op_tamper(w, 2, true, {{Edit::Insert, 70, 0x55}, {Edit::Erase, 90, 0}});
        op_deliver(w, 3);
        op_deliver(w, 2);
        save("reasm-tamper", w);
    }
    {
        Writer w = start(Mode::Reassembly);
        w.u8(1);  // 2 pending
        for (uint16_t f : {1, 2, 3}) op_encode(w, PacketType::Snapshot, kMasterSender, f, frag3, 0, snap);
        for (uint16_t i : {0, 3, 6, 1, 2, 4}) op_deliver(w, i);
        save("reasm-evict", w);
    }
    {
        Writer w = start(Mode::Reassembly);
        w.u8(7);
        op_encode(w, PacketType::Hello, 2, 0, 200, kEncodeDeliverNow, hello);
        op_encode(w, PacketType::FrameDone, 2, 4242, 200, kEncodeDeliverNow, report);
        op_encode(w, PacketType::Snapshot, kMasterSender, 4243, 1400, kEncodeDeliverNow, snap_small);
        op_encode(w, PacketType::Quit, kMasterSender, 4243, 1400, kEncodeDeliverNow, {});
        op_encode(w, PacketType::Heartbeat, 2, 4243, 600, 0, {}, 3000);  // a long padded message
        for (uint16_t i = 4; i < 11; ++i) op_deliver(w, i);
        save("reasm-kinds", w);
    }

    // Message payloads.
    {
        Writer w = start(Mode::Payload);
        w.u8(static_cast<uint8_t>(PayloadKind::Snapshot));
        w.bytes(snap);
        save("payload-snapshot", w);
    }
    {
        Writer w = start(Mode::Payload);
        w.u8(static_cast<uint8_t>(PayloadKind::Snapshot));
        w.bytes(snap_small);
        save("payload-snapshot-empty", w);
    }
    {
        Writer w = start(Mode::Payload);
        w.u8(static_cast<uint8_t>(PayloadKind::Hello));
        w.bytes(hello);
        save("payload-hello", w);
    }
    {
        Writer w = start(Mode::Payload);
        w.u8(static_cast<uint8_t>(PayloadKind::FrameReport));
        w.bytes(report);
        save("payload-frame-report", w);
    }
    {
        Writer w = start(Mode::Payload);
        w.u8(static_cast<uint8_t>(PayloadKind::Welcome));
        w.bytes(encode_welcome({2, 1234}));
        save("payload-welcome", w);
    }
    {
        Writer w = start(Mode::Payload);
        w.u8(static_cast<uint8_t>(PayloadKind::Present));
        w.bytes(encode_present({4242}));
        save("payload-present", w);
    }
    {
        Writer w = start(Mode::Raw);
        w.bytes(encode(PacketType::Present, kMasterSender, 4242, encode_present({4242}), 1400)[0]);
        save("raw-present", w);
    }
    // A slave's handshake with a master that restarts, then a replay of the old session.
    {
        Writer w = start(Mode::Sessions);
        w.u8(0);  // slave role
        auto step = [&](uint8_t type, uint16_t sender, uint8_t session, uint8_t to, uint32_t seq, uint16_t dt) {
            w.u8(type);
            w.u16(sender);
            w.u8(session);
            w.u8(to);
            w.u32(seq);
            w.u16(dt);
        };
        step(0, 1, 1, 0, 0, 1);    // snapshot of an unknown master: unverified
        step(1, 1, 1, 1, 1, 1);    // its welcome to us: opens
        step(0, 1, 1, 0, 2, 1);    // accepted
        step(0, 1, 1, 0, 2, 1);    // duplicate
        step(1, 1, 2, 1, 0, 1);    // a restarted master welcomes us
        step(0, 1, 1, 0, 3, 900);  // the old session: stale
        save("sessions-restart", w);
    }
    // Protocol scripts: a handshake, two frames and a quit; then one with losses, a replayed
    // hello, a master restart and a forged report.
    {
        Writer w = start(Mode::Protocol);
        w.u8(0);  // one channel
        auto op = [&](ProtocolOp o) { w.u8(static_cast<uint8_t>(o)); };
        op(ProtocolOp::Tick), w.u16(0);                    // hello to session 0
        for (int i = 0; i < 3; ++i) op(ProtocolOp::Next);  // welcome, confirming hello, joined
        for (int f = 0; f < 2; ++f) {
            op(ProtocolOp::Frame);
            op(ProtocolOp::Next);  // the snapshot: rendered and reported
            op(ProtocolOp::Next);  // the report
            op(ProtocolOp::Tick), w.u16(40);
        }
        op(ProtocolOp::Quit);
        op(ProtocolOp::Next), op(ProtocolOp::Next);
        op(ProtocolOp::Tick), w.u16(60);
        op(ProtocolOp::Tick), w.u16(400);
        save("protocol-session", w);
    }
    {
        Writer w = start(Mode::Protocol);
        w.u8(1);  // two channels
        auto op = [&](ProtocolOp o) { w.u8(static_cast<uint8_t>(o)); };
        op(ProtocolOp::Tick), w.u16(0);
        op(ProtocolOp::Drop);  // channel 0's hello is lost
        for (int i = 0; i < 3; ++i) op(ProtocolOp::Next);
        op(ProtocolOp::Replay), w.u16(1);  // a hello again
        op(ProtocolOp::Tick), w.u16(120);
        for (int i = 0; i < 6; ++i) op(ProtocolOp::Next);
        op(ProtocolOp::Frame);
        for (int i = 0; i < 4; ++i) op(ProtocolOp::Next);
        op(ProtocolOp::Restart), w.u8(2);  // a new master
        op(ProtocolOp::Tick), w.u16(1100);
        for (int i = 0; i < 8; ++i) op(ProtocolOp::Next);
        op(ProtocolOp::Forge), w.u8(1), w.u8(0), w.u8(1), w.u16(0), w.u16(3), w.u8(1), w.u8(2), w.u8(3);
        op(ProtocolOp::Next);
        op(ProtocolOp::Tick), w.u16(2500);
        save("protocol-restarts", w);
    }
    // The swap lock: two channels, three frames; a present is lost (the next snapshot implies
    // it), another repeated, and a forged present of a later frame.
    {
        Writer w = start(Mode::Protocol);
        w.u8(1);  // two channels
        auto op = [&](ProtocolOp o) { w.u8(static_cast<uint8_t>(o)); };
        op(ProtocolOp::Tick), w.u16(0);
        for (int i = 0; i < 6; ++i) op(ProtocolOp::Next);  // both handshakes
        for (int f = 0; f < 3; ++f) {
            op(ProtocolOp::Frame);
            op(ProtocolOp::Next), op(ProtocolOp::Next);  // the snapshot at both: two reports
            op(ProtocolOp::Next), op(ProtocolOp::Next);  // the reports: the present goes out
            op(f == 1 ? ProtocolOp::Drop : ProtocolOp::Next);
            op(ProtocolOp::Next);
            op(ProtocolOp::Tick), w.u16(120);  // a resent present
            op(ProtocolOp::Next), op(ProtocolOp::Next);
        }
        op(ProtocolOp::Forge), w.u8(3), w.u8(2), w.u8(0), w.u16(9), w.u16(8);
        for (int b = 0; b < 8; ++b) w.u8(b == 0 ? 9 : 0);
        op(ProtocolOp::Next), op(ProtocolOp::Next);
        op(ProtocolOp::Quit);
        for (int i = 0; i < 4; ++i) op(ProtocolOp::Next);
        op(ProtocolOp::Tick), w.u16(400);
        save("protocol-swap-lock", w);
    }
    std::printf("cupola-fuzz-wire-corpus: %d seeds written to %s\n", written, dir.c_str());
    return 0;
}

// libFuzzer target cupola-fuzz-wire: the wire protocol's receiving side under hostile input.
// The first input byte picks a mode (the format is in fuzz_wire_format.hpp):
//   Raw        raw bytes -> PacketCodec::decode, which must reject or accept cleanly;
//   RawSigned  the same with a correct tag, so the checks after authentication are reached;
//   Reassembly a script of messages encoded with PacketCodec::encode (real key, fuzz-chosen type,
//              sender, frame, sizes and payloads), delivered in fuzz-chosen order, duplicated, or
//              tampered with at fuzz-chosen byte positions and re-signed (the harness recomputes
//              the HMAC over the bytes before the tag: no header offset is known here), all
//              decoded and fed to one Reassembler;
//   Payload    bytes -> decode_snapshot / decode_hello / decode_frame_report / decode_welcome /
//              decode_present.
//   Sessions   a script of authentic headers through the session guard (replay and restart rules).
//   Protocol   a master and its slaves (MasterSession, SlaveSession) under a fuzz-chosen schedule of
//              deliveries, losses, replays, forged bodies, restarts and time (fuzz_protocol.cpp).
// Checked invariants (a violation prints what failed and aborts, which libFuzzer reports):
//   * an accepted datagram keeps decode's contract (fragment index < count, the fragment lies
//     inside the message, message length <= kMaxMessageLength, payload size = payload_length);
//   * a message just encoded, decoded fragment by fragment in order into a fresh Reassembler,
//     comes out whole and equal, on the last fragment only;
//   * a message the Reassembler returns matches the completing packet (type, sender, frame,
//     message_length);
//   * every payload decoder throws WireError or returns; what it returns encodes back to the
//     very same bytes (and for snapshots to the same snapshot_hash and an equal Snapshot).
// ASan/UBSan (with -fno-sanitize-recover=all) turn memory errors and UB into crashes.
#include <sodium.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include <spdlog/spdlog.h>

#include "fuzz_protocol.hpp"
#include "fuzz_wire_format.hpp"
#include "session/handshake.hpp"
#include "wire/byte_io.hpp"
#include "wire/packet.hpp"
#include "wire/reassembler.hpp"
#include "wire/reports.hpp"
#include "wire/session_guard.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;
using namespace cupola::fuzz;

namespace {

[[noreturn]] void violated(const char* what) {
    std::fprintf(stderr, "cupola-fuzz-wire: invariant violated: %s\n", what);
    std::fflush(stderr);
    std::abort();
}
#define FUZZ_CHECK(cond)              \
    do {                              \
        if (!(cond)) violated(#cond); \
    } while (0)

const PacketCodec& codec() {
    static const PacketCodec c(kClusterId, harness_key());
    return c;
}

// Replaces the last kTagSize bytes by the HMAC over everything before them (what a sender with
// the key would do). Too-short datagrams are left alone.
void resign(std::vector<uint8_t>& d) {
    if (d.size() < kTagSize) return;
    const size_t body = d.size() - kTagSize;
    crypto_auth_hmacsha256(d.data() + body, d.data(), body, harness_key().data());
}

void check_contract(const Packet& p) {
    const PacketHeader& h = p.header;
    FUZZ_CHECK(p.payload.size() == h.payload_length);
    FUZZ_CHECK(h.fragment_count >= 1);
    FUZZ_CHECK(h.fragment_index < h.fragment_count);
    FUZZ_CHECK(static_cast<uint64_t>(h.fragment_offset) + h.payload_length <= h.message_length);
    FUZZ_CHECK(h.message_length <= kMaxMessageLength);
    FUZZ_CHECK(h.fragment_count != 1 || (h.fragment_offset == 0 && h.payload_length == h.message_length));
}

void check_snapshot(const uint8_t* data, size_t size) {
    Snapshot s;
    try {
        s = decode_snapshot(data, size);
    } catch (const WireError&) {
        return;
    }
    const std::vector<uint8_t> original(data, data + size);
    const std::vector<uint8_t> again = encode_snapshot(s);
    FUZZ_CHECK(again == original);
    FUZZ_CHECK(snapshot_hash(again) == snapshot_hash(original));
    Snapshot s2;
    try {
        s2 = decode_snapshot(again.data(), again.size());
    } catch (const WireError&) {
        violated("re-encoded snapshot no longer decodes");
    }
    FUZZ_CHECK(s2 == s);
}

void check_hello(const std::vector<uint8_t>& payload) {
    HelloMessage m;
    try {
        m = decode_hello(payload);
    } catch (const WireError&) {
        return;
    }
    FUZZ_CHECK(encode_hello(m) == payload);
}

void check_frame_report(const std::vector<uint8_t>& payload) {
    FrameReport rep;
    try {
        rep = decode_frame_report(payload);
    } catch (const WireError&) {
        return;
    }
    const std::vector<uint8_t> again = encode_frame_report(rep);
    FUZZ_CHECK(again == payload);
    try {
        (void)decode_frame_report(again);
    } catch (const WireError&) {
        violated("re-encoded frame report no longer decodes");
    }
}

void check_present(const std::vector<uint8_t>& payload) {
    PresentMessage m;
    try {
        m = decode_present(payload);
    } catch (const WireError&) {
        return;
    }
    FUZZ_CHECK(encode_present(m) == payload);
}

void check_welcome(const std::vector<uint8_t>& payload) {
    WelcomeMessage m;
    try {
        m = decode_welcome(payload);
    } catch (const WireError&) {
        return;
    }
    FUZZ_CHECK(encode_welcome(m) == payload);
}

// The session guard under any sequence of authentic headers: it never accepts a session that the
// policy did not open, never accepts a datagram addressed to another session (welcomes for others
// are ignored), and once a peer moved on its old session is never accepted again.
void run_sessions(Reader& r) {
    const bool master_role = r.u8() & 1;
    constexpr uint64_t kSelf = 0x5E1F;
    const uint64_t sessions[4] = {0, 0xA1, 0xA2, 0xA3};
    const uint64_t targets[3] = {0, kSelf, 0x0DD};
    SessionGuard g(kSelf, master_role ? master_open_policy(kSelf) : slave_open_policy(kSelf));
    std::map<uint16_t, std::set<uint64_t>> retired;
    uint64_t now = 0;
    for (int step = 0; step < 256 && !r.empty(); ++step) {
        PacketHeader h;
        const uint8_t t = r.u8();
        h.type = (t & 1) ? PacketType::Welcome : (t & 2) ? PacketType::Hello : PacketType::Snapshot;
        h.sender = (r.u16() & 1) ? kMasterSender : 3;
        h.session = sessions[r.u8() % 4];
        h.to_session = targets[r.u8() % 3];
        h.sequence = r.u32();
        now += static_cast<uint64_t>(r.u16()) * 1000000ull;
        const uint64_t before = g.peer_session(h.sender);
        const GuardVerdict v = g.check(h, now);
        const uint64_t after = g.peer_session(h.sender);
        const bool accepted = v.kind == GuardVerdict::Accept || v.kind == GuardVerdict::Opened;
        if (accepted) {
            FUZZ_CHECK(h.session != 0);
            FUZZ_CHECK(h.to_session == 0 || h.to_session == kSelf);
            FUZZ_CHECK(after == h.session);
            FUZZ_CHECK(!retired[h.sender].count(h.session));
        }
        if (v.kind == GuardVerdict::Opened) {
            FUZZ_CHECK(master_role ? h.type == PacketType::Hello : h.type == PacketType::Welcome);
            FUZZ_CHECK(h.to_session == kSelf);
        }
        if (before != after) {
            FUZZ_CHECK(v.kind == GuardVerdict::Opened);
            if (before != 0) retired[h.sender].insert(before);
        }
    }
}

// What the master/slave would do with a reassembled message: decode its body.
void consume(const Message& m) {
    switch (m.type) {
        case PacketType::Snapshot:
            check_snapshot(m.payload.data(), m.payload.size());
            break;
        case PacketType::Hello:
            check_hello(m.payload);
            break;
        case PacketType::FrameDone:
            check_frame_report(m.payload);
            break;
        case PacketType::Welcome:
            check_welcome(m.payload);
            break;
        case PacketType::Present:
            check_present(m.payload);
            break;
        default:
            break;
    }
}

// decode -> contract -> reassembler -> message checks -> body decoders.
void deliver(const std::vector<uint8_t>& datagram, Reassembler& re) {
    DecodeResult res = codec().decode(datagram.data(), datagram.size());
    if (!res.packet) {
        FUZZ_CHECK(static_cast<int>(res.reason) >= 0 && res.reason < RejectReason::Count);
        FUZZ_CHECK(reject_reason_name(res.reason) != nullptr);  // what the counters log
        return;
    }
    check_contract(*res.packet);
    const PacketHeader h = res.packet->header;
    FUZZ_CHECK(packet_type_name(h.type) != nullptr);
    std::optional<Message> m = re.add(std::move(*res.packet));
    if (!m) return;
    FUZZ_CHECK(m->type == h.type);
    FUZZ_CHECK(m->sender == h.sender);
    FUZZ_CHECK(m->frame == h.frame);
    FUZZ_CHECK(m->payload.size() == h.message_length);
    consume(*m);
}

void run_raw(Reader& r, bool sign) {
    std::vector<uint8_t> d = r.rest();
    if (sign) resign(d);
    Reassembler re;
    deliver(d, re);
}

// Encoded fragments, decoded in order into a fresh Reassembler, give back the message exactly.
void check_round_trip(const std::vector<std::vector<uint8_t>>& datagrams, PacketType type, uint16_t sender,
                      uint64_t frame, const std::vector<uint8_t>& message) {
    Reassembler fresh;
    for (size_t i = 0; i < datagrams.size(); ++i) {
        DecodeResult res = codec().decode(datagrams[i].data(), datagrams[i].size());
        if (!res.packet) {
            // A type the decoder does not know is refused (for every fragment alike); any other
            // refusal of an authentic, untouched datagram is a bug.
            FUZZ_CHECK(res.reason == RejectReason::BadType);
            return;
        }
        check_contract(*res.packet);
        std::optional<Message> m = fresh.add(std::move(*res.packet));
        if (i + 1 < datagrams.size()) {
            FUZZ_CHECK(!m);
            continue;
        }
        FUZZ_CHECK(m.has_value());
        FUZZ_CHECK(m->type == type);
        FUZZ_CHECK(m->sender == sender);
        FUZZ_CHECK(m->frame == frame);
        FUZZ_CHECK(m->payload == message);
    }
}

void run_reassembly(Reader& r) {
    Reassembler re(1 + r.u8() % kMaxPendingSpan);
    std::vector<std::vector<uint8_t>> pool;
    for (size_t step = 0; step < kMaxSteps && !r.empty(); ++step) {
        switch (static_cast<Op>(r.u8() % kOpCount)) {
            case Op::Encode: {
                const auto type = static_cast<PacketType>(r.u8());
                const uint16_t sender = r.u16();
                const uint64_t frame = r.u16();
                uint32_t sequence = r.u32();
                const size_t max_datagram = kHeaderSize + kTagSize + 16 + r.u16() % kMaxDatagramSpan;
                const uint8_t flags = r.u8();
                std::vector<uint8_t> message = r.bytes(r.u16());
                const size_t pad = r.u16() % kMaxPad;
                for (size_t i = 0; i < pad; ++i) message.push_back(static_cast<uint8_t>(i * 131 + message.size()));
                auto datagrams = codec().encode(type, sender, frame, message, max_datagram, &sequence);
                FUZZ_CHECK(!datagrams.empty());
                for (const auto& d : datagrams) FUZZ_CHECK(d.size() <= max_datagram);
                check_round_trip(datagrams, type, sender, frame, message);
                if (flags & kEncodeDeliverNow)
                    for (const auto& d : datagrams) deliver(d, re);
                for (auto& d : datagrams)
                    if (pool.size() < kMaxPool) pool.push_back(std::move(d));
                break;
            }
            case Op::Deliver: {
                const uint16_t sel = r.u16();
                if (!pool.empty()) deliver(pool[sel % pool.size()], re);
                break;
            }
            case Op::Tamper: {
                const uint16_t sel = r.u16();
                const uint8_t flags = r.u8();
                const size_t edits = 1 + r.u8() % kMaxEdits;
                std::vector<uint8_t> d;
                if (!pool.empty()) d = pool[sel % pool.size()];
                for (size_t e = 0; e < edits; ++e) {
                    const auto kind = static_cast<Edit>(r.u8() % kEditCount);
                    const uint16_t pos = r.u16();
                    const uint8_t value = r.u8();
                    if (d.size() < kTagSize) continue;
                    const size_t body = d.size() - kTagSize;  // the signed part; the tag follows
                    switch (kind) {
                        case Edit::Set:
                            if (body) d[pos % body] = value;
                            break;
                        case Edit::Xor:
                            if (body) d[pos % body] ^= value;
                            break;
                        case Edit::Insert:
                            d.insert(d.begin() + static_cast<std::ptrdiff_t>(pos % (body + 1)), value);
                            break;
                        case Edit::Erase:
                            if (body) d.erase(d.begin() + static_cast<std::ptrdiff_t>(pos % body));
                            break;
                    }
                }
                if (d.size() < kTagSize) break;
                resign(d);
                deliver(d, re);
                if ((flags & kTamperKeep) && pool.size() < kMaxPool) pool.push_back(std::move(d));
                break;
            }
        }
    }
}

void run_payload(Reader& r) {
    const auto kind = static_cast<PayloadKind>(r.u8() % kPayloadKindCount);
    const std::vector<uint8_t> payload = r.rest();
    switch (kind) {
        case PayloadKind::Snapshot:
            check_snapshot(payload.data(), payload.size());
            break;
        case PayloadKind::Hello:
            check_hello(payload);
            break;
        case PayloadKind::FrameReport:
            check_frame_report(payload);
            break;
        case PayloadKind::Welcome:
            check_welcome(payload);
            break;
        case PayloadKind::Present:
            check_present(payload);
            break;
    }
}

}  // namespace

// The sessions log what an operator would want to see; here that is noise.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    spdlog::set_level(spdlog::level::off);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    Reader r(data, size);
    switch (static_cast<Mode>(r.u8() % kModeCount)) {
        case Mode::Raw:
            run_raw(r, false);
            break;
        case Mode::RawSigned:
            run_raw(r, true);
            break;
        case Mode::Reassembly:
            run_reassembly(r);
            break;
        case Mode::Sessions:
            run_sessions(r);
            break;
        case Mode::Payload:
            run_payload(r);
            break;
        case Mode::Protocol:
            run_protocol(r);
            break;
    }
    return 0;
}

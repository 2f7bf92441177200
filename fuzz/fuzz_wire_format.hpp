#pragma once
// The input format of the wire-protocol fuzzer (fuzz_wire_decoder.cpp), shared with its seed
// generator (make_corpus.cpp) so that both read and write the same scripts: the mode byte, the
// reassembly script's operations, the payload selectors, and the fixed cluster id and key the
// harness signs with. Nothing here knows the datagram header's layout: datagrams are made by
// PacketCodec::encode and tampered with at fuzz-chosen positions, and the only fixed fact used
// is that the HMAC tag is the last kTagSize bytes and covers everything before it.
//
// Input = one mode byte (taken modulo kModeCount), then:
//   Mode::Raw        the rest is one datagram, given to PacketCodec::decode as it is.
//   Mode::RawSigned  the rest is one datagram whose last kTagSize bytes the harness replaces by
//                    the correct HMAC over the bytes before them, so that the checks behind the
//                    authentication are reached.
//   Mode::Reassembly u8 max_pending_sel (Reassembler(1 + sel % kMaxPendingSpan)), then a script
//                    of operations until the input ends (at most kMaxSteps), each u8 op % kOpCount:
//     Op::Encode   u8 type (raw PacketType value), u16 sender, u16 frame, u32 first_sequence,
//                  u16 max_datagram_sel (max_datagram = kHeaderSize + kTagSize + 16 +
//                  sel % kMaxDatagramSpan), u8 flags (kEncodeDeliverNow), u16 literal_len,
//                  literal_len message bytes (fewer if the input ends), u16 pad_sel
//                  (sel % kMaxPad pattern bytes appended to the message). The datagrams are
//                  appended to the pool (while it holds fewer than kMaxPool).
//     Op::Deliver  u16 pool_sel: decode pool[sel % size] and add it to the reassembler.
//     Op::Tamper   u16 pool_sel, u8 flags (kTamperKeep), u8 edits_sel (1 + sel % kMaxEdits
//                  edits), each edit u8 kind % kEditCount, u16 position, u8 value; then the tag
//                  is recomputed and the datagram decoded and added to the reassembler.
//   Mode::Payload    u8 kind % kPayloadKindCount (PayloadKind), the rest is a message payload.
//   Mode::Sessions   u8 role (even: slave policy, odd: master policy), then steps of
//                    {u8 type, u16 sender, u8 session_sel, u8 to_sel, u32 sequence, u16 dt_ms}
//                    through one SessionGuard (wire/session_guard.hpp).
//   Mode::Protocol   u8 channels_sel (1 + sel % kMaxProtocolChannels slave processes, channels 0..),
//                    then steps until the input ends (at most kMaxSteps), each u8 op % kProtocolOpCount
//                    (fuzz_protocol.hpp; datagrams in flight are kept in send order):
//     ProtocolOp::Tick     u16 dt_ms: time advances, then every session's tick() runs.
//     ProtocolOp::Next     the oldest datagram in flight arrives (through the receiver's guard).
//     ProtocolOp::Drop     the oldest datagram in flight is lost.
//     ProtocolOp::Replay   u16 sel: a datagram that left earlier (the sel % size-th) arrives again.
//     ProtocolOp::Frame    the master ends its frame (if any) and starts the next.
//     ProtocolOp::Quit     the master starts telling the slaves to quit.
//     ProtocolOp::Restart  u8 who: who % (n + 1) == n restarts the master, else that slave.
//     ProtocolOp::Forge    u8 type, u8 from_sel, u8 to_sel, u16 frame, u16 len, len body bytes: an
//                          authentic message with that body (from_sel % (n + 1) == n: the master's).
// Integers are little-endian; reading past the end yields zeros.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "wire/packet.hpp"

namespace cupola::fuzz {

constexpr uint32_t kClusterId = 0x5A5A5546u;

inline AuthKey harness_key() {
    AuthKey k{};
    for (size_t i = 0; i < k.size(); ++i) k[i] = static_cast<uint8_t>(0xA7 ^ (i * 29 + 3));
    return k;
}

enum class Mode : uint8_t { Raw = 0, RawSigned = 1, Reassembly = 2, Payload = 3, Sessions = 4, Protocol = 5 };
constexpr uint8_t kModeCount = 6;

enum class Op : uint8_t { Encode = 0, Deliver = 1, Tamper = 2 };
constexpr uint8_t kOpCount = 3;

enum class Edit : uint8_t { Set = 0, Xor = 1, Insert = 2, Erase = 3 };
constexpr uint8_t kEditCount = 4;

enum class PayloadKind : uint8_t { Snapshot = 0, Hello = 1, FrameReport = 2, Welcome = 3, Present = 4 };
constexpr uint8_t kPayloadKindCount = 5;

enum class ProtocolOp : uint8_t {
    Tick = 0,
    Next = 1,
    Drop = 2,
    Replay = 3,
    Frame = 4,
    Quit = 5,
    Restart = 6,
    Forge = 7
};
constexpr uint8_t kProtocolOpCount = 8;
constexpr uint8_t kMaxProtocolChannels = 3;

constexpr uint8_t kEncodeDeliverNow = 1;  // also decode + add every fragment, in order, at once
constexpr uint8_t kTamperKeep = 1;        // put the tampered datagram back into the pool

constexpr size_t kMaxPendingSpan = 16;
constexpr size_t kMaxSteps = 256;
constexpr size_t kMaxPool = 1024;
constexpr size_t kMaxDatagramSpan = 1500;
constexpr size_t kMaxPad = 4096;
constexpr size_t kMaxEdits = 8;

// Reads the fuzz input front to back; past the end every read yields zeros.
class Reader {
public:
    Reader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    bool empty() const { return pos_ >= size_; }
    size_t remaining() const { return size_ - pos_; }
    uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
    uint16_t u16() { return static_cast<uint16_t>(le(2)); }
    uint32_t u32() { return static_cast<uint32_t>(le(4)); }
    uint64_t u64() { return le(8); }
    // Up to n bytes (fewer when the input ends first).
    std::vector<uint8_t> bytes(size_t n) {
        n = n < remaining() ? n : remaining();
        std::vector<uint8_t> v(data_ + pos_, data_ + pos_ + n);
        pos_ += n;
        return v;
    }
    std::vector<uint8_t> rest() { return bytes(remaining()); }

private:
    uint64_t le(int n) {
        uint64_t v = 0;
        for (int i = 0; i < n; ++i) v |= static_cast<uint64_t>(u8()) << (8 * i);
        return v;
    }
    const uint8_t* data_;
    size_t size_;
    size_t pos_ = 0;
};

// Writes inputs in the same format (for the seed generator).
class Writer {
public:
    void u8(uint8_t v) { out.push_back(v); }
    void u16(uint16_t v) { le(v, 2); }
    void u32(uint32_t v) { le(v, 4); }
    void u64(uint64_t v) { le(v, 8); }
    void bytes(const std::vector<uint8_t>& v) { out.insert(out.end(), v.begin(), v.end()); }
    std::vector<uint8_t> out;

private:
    void le(uint64_t v, int n) {
        for (int i = 0; i < n; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
};

}  // namespace cupola::fuzz

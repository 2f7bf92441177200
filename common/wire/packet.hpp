#pragma once
// One UDP datagram of the Cupola wire protocol (version 4: the snapshot carries the night sky's brightness). All
// fields little-endian.
//
//  offset size field
//   0      4   magic            0x4C505543 ("CUPL" in byte order)
//   4      2   version          kProtocolVersion
//   6      1   type             PacketType
//   7      1   flags            0 (reserved)
//   8      4   cluster_id       from the cluster config; other clusters' packets are dropped
//  12      2   sender           channel id, or kMasterSender
//  14      2   fragment_index   0-based
//  16      2   fragment_count   >= 1
//  18      2   reserved         0
//  20      4   sequence         per sender session, +1 per datagram (replay window)
//  24      8   session          random nonce of the sending process, new at every start
//  32      8   to_session       the addressee's session this answers (0: anyone; see session_guard)
//  40      8   frame            frame number the message belongs to
//  48      4   message_length   length of the whole (reassembled) message payload
//  52      4   fragment_offset  where this fragment's payload starts in the message
//  56      4   payload_length   bytes of payload in this datagram
//  60      n   payload
//  60+n   32   tag              HMAC-SHA256 (libsodium) over bytes [0, 60+n), shared key file
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cupola {

constexpr uint32_t kMagic = 0x4C505543u;
constexpr uint16_t kProtocolVersion = 4;
constexpr uint16_t kMasterSender = 0xFFFF;
constexpr size_t kHeaderSize = 60;
constexpr size_t kTagSize = 32;
constexpr size_t kMaxMessageLength = 16u << 20;  // 16 MiB

enum class PacketType : uint8_t {
    Snapshot = 1,    // master -> slaves: Snapshot (possibly fragmented)
    Quit = 2,        // master -> slaves: stop after this frame
    Welcome = 3,     // master -> one slave (to_session): proves the master's session is live now
    Present = 4,     // master -> slaves: PresentMessage, show frame N now (swap lock, docs/SWAP_LOCK.md)
    Hello = 16,      // slave -> master: channel joins or rejoins
    Heartbeat = 17,  // reserved: a valid type on the wire, but nothing sends it and a master logs it as
                     // unexpected (a live slave reports every frame; hellos cover one without frames)
    FrameDone = 18,  // slave -> master: FrameReport
    QuitAck = 19,    // slave -> master: quit received
};
const char* packet_type_name(PacketType t);

using AuthKey = std::array<uint8_t, 32>;

// A fresh random 64-bit session nonce (libsodium's CSPRNG), never 0.
uint64_t new_session_nonce();

struct PacketHeader {
    uint16_t version = kProtocolVersion;
    PacketType type = PacketType::Snapshot;
    uint8_t flags = 0;
    uint32_t cluster_id = 0;
    uint16_t sender = 0;
    uint16_t fragment_index = 0;
    uint16_t fragment_count = 1;
    uint32_t sequence = 0;
    uint64_t session = 0;
    uint64_t to_session = 0;
    uint64_t frame = 0;
    uint32_t message_length = 0;
    uint32_t fragment_offset = 0;
    uint32_t payload_length = 0;
};

struct Packet {
    PacketHeader header;
    std::vector<uint8_t> payload;  // this datagram's part of the message
};

// Why a datagram was refused; each reason has its own counter.
// The first seven come from decoding one datagram; the last three from the session guard
// (common/wire/session_guard.hpp), which sees the sender's session and sequence.
enum class RejectReason {
    BadMagic,
    BadVersion,
    WrongCluster,
    BadLength,
    BadAuth,
    BadType,
    BadFragment,
    Replayed,        // a sequence number of the sender's session already seen (long ago) or too old
    StaleSession,    // from, or addressed to, a session that has ended (a restart happened since)
    UnknownSession,  // from a session not (yet) established by the Hello/Welcome handshake
    Count
};
const char* reject_reason_name(RejectReason r);

struct DecodeResult {
    std::optional<Packet> packet;
    RejectReason reason = RejectReason::BadMagic;  // meaningful when !packet
};

class PacketCodec {
public:
    // session: this process's nonce, written into every datagram it encodes.
    PacketCodec(uint32_t cluster_id, const AuthKey& key, uint64_t session = 0)
        : cluster_id_(cluster_id), key_(key), session_(session) {}

    // Splits a message into datagrams of at most max_datagram bytes (header + payload + tag).
    // Sequence numbers are taken from *sequence and advanced.
    std::vector<std::vector<uint8_t>> encode(PacketType type, uint16_t sender, uint64_t frame,
                                             const std::vector<uint8_t>& message, size_t max_datagram,
                                             uint32_t* sequence, uint64_t to_session = 0) const;

    // Verifies magic, version, cluster, lengths and the tag (in constant time), in that order.
    DecodeResult decode(const uint8_t* data, size_t size) const;

    uint32_t cluster_id() const { return cluster_id_; }
    uint64_t session() const { return session_; }

private:
    uint32_t cluster_id_;
    AuthKey key_;
    uint64_t session_;
};

}  // namespace cupola

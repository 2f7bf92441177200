#pragma once
// One UDP datagram of the Cupola wire protocol (version 1). All fields little-endian.
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
//  20      4   sequence         per sender, +1 per datagram
//  24      8   frame            frame number the message belongs to
//  32      4   message_length   length of the whole (reassembled) message payload
//  36      4   fragment_offset  where this fragment's payload starts in the message
//  40      4   payload_length   bytes of payload in this datagram
//  44      n   payload
//  44+n   32   tag              HMAC-SHA256 (libsodium) over bytes [0, 44+n), shared key file
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cupola {

constexpr uint32_t kMagic = 0x4C505543u;
constexpr uint16_t kProtocolVersion = 1;
constexpr uint16_t kMasterSender = 0xFFFF;
constexpr size_t kHeaderSize = 44;
constexpr size_t kTagSize = 32;
constexpr size_t kMaxMessageLength = 16u << 20;  // 16 MiB

enum class PacketType : uint8_t {
    Snapshot = 1,   // master -> slaves: Snapshot (possibly fragmented)
    Quit = 2,       // master -> slaves: stop after this frame
    Hello = 16,     // slave -> master: channel joins or rejoins
    Heartbeat = 17, // slave -> master: still alive (while idle)
    FrameDone = 18, // slave -> master: FrameReport
};
const char* packet_type_name(PacketType t);

using AuthKey = std::array<uint8_t, 32>;

// Reads a key file: 64 hexadecimal digits (whitespace ignored). Throws naming the file.
AuthKey load_key_file(const std::string& path);

struct PacketHeader {
    uint16_t version = kProtocolVersion;
    PacketType type = PacketType::Snapshot;
    uint8_t flags = 0;
    uint32_t cluster_id = 0;
    uint16_t sender = 0;
    uint16_t fragment_index = 0;
    uint16_t fragment_count = 1;
    uint32_t sequence = 0;
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
enum class RejectReason { BadMagic, BadVersion, WrongCluster, BadLength, BadAuth, BadType, BadFragment, Count };
const char* reject_reason_name(RejectReason r);

struct DecodeResult {
    std::optional<Packet> packet;
    RejectReason reason = RejectReason::BadMagic;  // meaningful when !packet
};

class PacketCodec {
public:
    PacketCodec(uint32_t cluster_id, const AuthKey& key) : cluster_id_(cluster_id), key_(key) {}

    // Splits a message into datagrams of at most max_datagram bytes (header + payload + tag).
    // Sequence numbers are taken from *sequence and advanced.
    std::vector<std::vector<uint8_t>> encode(PacketType type, uint16_t sender, uint64_t frame,
                                             const std::vector<uint8_t>& message, size_t max_datagram,
                                             uint32_t* sequence) const;

    // Verifies magic, version, cluster, lengths and the tag (in constant time), in that order.
    DecodeResult decode(const uint8_t* data, size_t size) const;

    uint32_t cluster_id() const { return cluster_id_; }

private:
    uint32_t cluster_id_;
    AuthKey key_;
};

}  // namespace cupola

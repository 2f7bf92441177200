#include "wire/packet.hpp"

#include <sodium.h>

#include <algorithm>
#include <stdexcept>

#include "wire/byte_io.hpp"

namespace cupola {

namespace {
struct SodiumInit {
    SodiumInit() {
        if (sodium_init() < 0) throw std::runtime_error("libsodium failed to initialise");
    }
};
void ensure_sodium() { static SodiumInit once; }

bool known_type(uint8_t t) {
    switch (static_cast<PacketType>(t)) {
        case PacketType::Snapshot:
        case PacketType::Quit:
        case PacketType::Welcome:
        case PacketType::Present:
        case PacketType::Hello:
        case PacketType::Heartbeat:
        case PacketType::FrameDone:
        case PacketType::QuitAck:
            return true;
    }
    return false;
}
}  // namespace

const char* packet_type_name(PacketType t) {
    switch (t) {
        case PacketType::Snapshot:
            return "snapshot";
        case PacketType::Quit:
            return "quit";
        case PacketType::Hello:
            return "hello";
        case PacketType::Heartbeat:
            return "heartbeat";
        case PacketType::FrameDone:
            return "frame-done";
        case PacketType::Welcome:
            return "welcome";
        case PacketType::QuitAck:
            return "quit-ack";
        case PacketType::Present:
            return "present";
    }
    return "unknown";
}

const char* reject_reason_name(RejectReason r) {
    switch (r) {
        case RejectReason::BadMagic:
            return "bad magic";
        case RejectReason::BadVersion:
            return "wrong protocol version";
        case RejectReason::WrongCluster:
            return "wrong cluster id";
        case RejectReason::BadLength:
            return "bad length";
        case RejectReason::BadAuth:
            return "authentication failed";
        case RejectReason::BadType:
            return "unknown packet type";
        case RejectReason::BadFragment:
            return "bad fragment";
        case RejectReason::Replayed:
            return "replayed";
        case RejectReason::StaleSession:
            return "stale session";
        case RejectReason::UnknownSession:
            return "unknown session";
        case RejectReason::Count:
            break;
    }
    return "?";
}

uint64_t new_session_nonce() {
    ensure_sodium();
    uint64_t n = 0;
    while (n == 0) randombytes_buf(&n, sizeof n);
    return n;
}

std::vector<std::vector<uint8_t>> PacketCodec::encode(PacketType type, uint16_t sender, uint64_t frame,
                                                      const std::vector<uint8_t>& message, size_t max_datagram,
                                                      uint32_t* sequence, uint64_t to_session) const {
    ensure_sodium();
    if (max_datagram < kHeaderSize + kTagSize + 16) throw std::invalid_argument("max_datagram too small");
    if (message.size() > kMaxMessageLength) throw std::invalid_argument("message too long");
    const size_t chunk = max_datagram - kHeaderSize - kTagSize;
    const size_t count = std::max<size_t>(1, (message.size() + chunk - 1) / chunk);
    if (count > 0xFFFF) throw std::invalid_argument("message needs too many fragments");
    std::vector<std::vector<uint8_t>> out;
    out.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const size_t off = i * chunk;
        const size_t len = std::min(chunk, message.size() - std::min(off, message.size()));
        std::vector<uint8_t> d;
        d.reserve(kHeaderSize + len + kTagSize);
        ByteWriter w(d);
        w.u32(kMagic);
        w.u16(kProtocolVersion);
        w.u8(static_cast<uint8_t>(type));
        w.u8(0);
        w.u32(cluster_id_);
        w.u16(sender);
        w.u16(static_cast<uint16_t>(i));
        w.u16(static_cast<uint16_t>(count));
        w.u16(0);
        w.u32((*sequence)++);
        w.u64(session_);
        w.u64(to_session);
        w.u64(frame);
        w.u32(static_cast<uint32_t>(message.size()));
        w.u32(static_cast<uint32_t>(off));
        w.u32(static_cast<uint32_t>(len));
        if (len) w.bytes(message.data() + off, len);
        uint8_t tag[kTagSize];
        crypto_auth_hmacsha256(tag, d.data(), d.size(), key_.data());
        w.bytes(tag, kTagSize);
        out.push_back(std::move(d));
    }
    return out;
}

DecodeResult PacketCodec::decode(const uint8_t* data, size_t size) const {
    ensure_sodium();
    DecodeResult res;
    auto reject = [&](RejectReason r) {
        res.reason = r;
        return res;
    };
    if (size < 4) return reject(RejectReason::BadLength);
    ByteReader r(data, size);
    if (r.u32("magic") != kMagic) return reject(RejectReason::BadMagic);
    if (size < kHeaderSize + kTagSize) return reject(RejectReason::BadLength);
    PacketHeader h;
    h.version = r.u16("version");
    if (h.version != kProtocolVersion) return reject(RejectReason::BadVersion);
    uint8_t type = r.u8("type");
    h.flags = r.u8("flags");
    h.cluster_id = r.u32("cluster_id");
    if (h.cluster_id != cluster_id_) return reject(RejectReason::WrongCluster);
    h.sender = r.u16("sender");
    h.fragment_index = r.u16("fragment_index");
    h.fragment_count = r.u16("fragment_count");
    r.u16("reserved");
    h.sequence = r.u32("sequence");
    h.session = r.u64("session");
    h.to_session = r.u64("to_session");
    h.frame = r.u64("frame");
    h.message_length = r.u32("message_length");
    h.fragment_offset = r.u32("fragment_offset");
    h.payload_length = r.u32("payload_length");
    if (static_cast<size_t>(h.payload_length) != size - kHeaderSize - kTagSize) return reject(RejectReason::BadLength);
    // Authenticate before trusting any other field.
    if (crypto_auth_hmacsha256_verify(data + size - kTagSize, data, size - kTagSize, key_.data()) != 0)
        return reject(RejectReason::BadAuth);
    if (!known_type(type)) return reject(RejectReason::BadType);
    h.type = static_cast<PacketType>(type);
    if (h.message_length > kMaxMessageLength || h.fragment_count == 0 || h.fragment_index >= h.fragment_count ||
        static_cast<uint64_t>(h.fragment_offset) + h.payload_length > h.message_length + 0ull ||
        (h.fragment_count == 1 && (h.fragment_offset != 0 || h.payload_length != h.message_length)))
        return reject(RejectReason::BadFragment);
    Packet p;
    p.header = h;
    p.payload.assign(data + kHeaderSize, data + kHeaderSize + h.payload_length);
    res.packet = std::move(p);
    return res;
}

}  // namespace cupola

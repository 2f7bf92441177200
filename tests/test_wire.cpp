// The wire protocol: snapshot encoding, packet framing, fragmentation, authentication and the
// rejection counters, on real UDP sockets where sockets are involved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <filesystem>
#include <fstream>
#include <bit>
#include <chrono>
#include <thread>
#include <sodium.h>

#include "net/key_file.hpp"
#include "net/udp_socket.hpp"
#include "net/wire_endpoint.hpp"
#include "support/wire_handshake.hpp"
#include "wire/byte_io.hpp"
#include "wire/packet.hpp"
#include "wire/reassembler.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;

namespace {

AuthKey key_of(uint8_t seed) {
    AuthKey k{};
    for (size_t i = 0; i < k.size(); ++i) k[i] = static_cast<uint8_t>(seed * 31 + i * 7);
    return k;
}

Snapshot sample_snapshot(size_t bodies) {
    Snapshot s;
    s.frame = 123456789012ull;
    s.sim_time_s = 765432101.123456789;
    s.camera_position_m = {1.4959787070001e11, -3.0e7, 1.0e-3};
    s.camera_orientation = glm::normalize(glm::dquat(0.9, 0.1, -0.3, 0.2));
    for (size_t i = 0; i < bodies; ++i) {
        BodyState b;
        b.id = static_cast<uint16_t>(i);
        b.position_m = {1e11 + i * 1234.5678, -2e10 / (i + 1.0), std::ldexp(1.0, static_cast<int>(i % 60))};
        b.orientation = glm::normalize(glm::dquat(1.0, 0.01 * i, 0.02, -0.03 * i));
        s.bodies.push_back(b);
    }
    s.settings.exposure = 2.5f;
    s.settings.star_magnitude_limit = 6.5f;
    s.settings.flags = 0xA5A5u;
    s.settings.glare_phase = 12.25f;
    s.settings.tone_white = 3.75f;
    s.settings.adapted_cd_m2 = 1234.5f;
    s.settings.twinkle_time_s = 17.125f;
    GlareSource sun;
    sun.body = 0;
    sun.direction = glm::normalize(glm::vec3(0.3f, -0.4f, 0.8f));
    sun.angular_radius = 4.65e-3f;
    sun.irradiance = {3.9f, 3.8f, 3.5f};
    sun.visible_fraction = 0.5f;
    sun.centroid_offset = {1e-3f, -2e-4f, 0.0f};
    sun.origin = GlareOrigin::Measured;
    sun.measured_frame = s.frame - 1;
    s.glare.push_back(sun);
    GlareSource sirius;
    sirius.star = 12;
    sirius.irradiance = {1e-9f, 1e-9f, 1.2e-9f};
    s.glare.push_back(sirius);
    return s;
}

}  // namespace

TEST(Snapshot, RoundTripIsExact) {
    const Snapshot s = sample_snapshot(3);
    const auto bytes = encode_snapshot(s);
    const Snapshot d = decode_snapshot(bytes.data(), bytes.size());
    EXPECT_EQ(d, s);
    // Doubles survive bit for bit (no float narrowing anywhere on the wire).
    EXPECT_EQ(std::bit_cast<uint64_t>(d.camera_position_m.x), std::bit_cast<uint64_t>(s.camera_position_m.x));
    EXPECT_EQ(snapshot_hash(bytes), snapshot_hash(encode_snapshot(d)));
    EXPECT_EQ(snapshot_hash(bytes).size(), 16u);
}

TEST(Snapshot, EncodingIsLittleEndian) {
    Snapshot s;
    s.frame = 0x0102030405060708ull;
    const auto bytes = encode_snapshot(s);
    ASSERT_GE(bytes.size(), 8u);
    for (int i = 0; i < 8; ++i) EXPECT_EQ(bytes[i], 8 - i);
}

TEST(Snapshot, DifferentStateGivesDifferentHash) {
    Snapshot a = sample_snapshot(2), b = a;
    b.camera_position_m.x = std::nextafter(b.camera_position_m.x, 0.0);
    EXPECT_NE(snapshot_hash(encode_snapshot(a)), snapshot_hash(encode_snapshot(b)));
}

TEST(Snapshot, MalformedPayloadsAreRefused) {
    const auto good = encode_snapshot(sample_snapshot(2));
    for (size_t cut : {size_t(0), size_t(7), size_t(40), good.size() - 1}) {
        EXPECT_THROW(decode_snapshot(good.data(), cut), WireError) << "cut at " << cut;
    }
    auto longer = good;
    longer.push_back(0);
    EXPECT_THROW(decode_snapshot(longer.data(), longer.size()), WireError);
    Snapshot nan = sample_snapshot(1);
    nan.camera_position_m.y = std::numeric_limits<double>::quiet_NaN();
    auto nb = encode_snapshot(nan);
    try {
        decode_snapshot(nb.data(), nb.size());
        FAIL();
    } catch (const WireError& e) {
        EXPECT_NE(std::string(e.what()).find("camera_position_m"), std::string::npos) << e.what();
    }
    Snapshot badq = sample_snapshot(1);
    badq.camera_orientation = glm::dquat(2.0, 0, 0, 0);
    auto qb = encode_snapshot(badq);
    EXPECT_THROW(decode_snapshot(qb.data(), qb.size()), WireError);
    // A body count that the payload cannot hold.
    auto huge = good;
    const size_t count_at = 8 + 8 + 24 + 32 + 32 + 4 * kOverlayCount;  // after the render settings
    huge[count_at] = 0xFF;
    huge[count_at + 1] = 0xFF;
    EXPECT_THROW(decode_snapshot(huge.data(), huge.size()), WireError);
    // Glare values a channel could not draw from are refused, naming the field.
    auto refused_field = [](const Snapshot& bad) -> std::string {
        const auto b = encode_snapshot(bad);
        try {
            decode_snapshot(b.data(), b.size());
        } catch (const WireError& e) {
            return e.what();
        }
        return "accepted";
    };
    Snapshot w = sample_snapshot(1);
    w.settings.tone_white = -1.0f;
    EXPECT_NE(refused_field(w).find("settings.tone_white"), std::string::npos) << refused_field(w);
    w = sample_snapshot(1);
    w.settings.adapted_cd_m2 = std::numeric_limits<float>::infinity();
    EXPECT_NE(refused_field(w).find("settings.adapted_cd_m2"), std::string::npos) << refused_field(w);
    Snapshot g = sample_snapshot(1);
    g.glare[0].visible_fraction = 1.5f;
    EXPECT_NE(refused_field(g).find("glare.visible_fraction"), std::string::npos) << refused_field(g);
    g = sample_snapshot(1);
    g.glare[0].direction = {0.0f, 0.0f, 2.0f};
    EXPECT_NE(refused_field(g).find("glare.direction"), std::string::npos) << refused_field(g);
    g = sample_snapshot(1);
    g.glare[1].irradiance.y = std::numeric_limits<float>::infinity();
    EXPECT_NE(refused_field(g).find("glare.irradiance"), std::string::npos) << refused_field(g);
    g = sample_snapshot(1);
    g.glare[0].origin = static_cast<GlareOrigin>(7);
    EXPECT_NE(refused_field(g).find("glare.origin"), std::string::npos) << refused_field(g);
}

TEST(Packet, SingleDatagramRoundTrip) {
    PacketCodec codec(77, key_of(1));
    uint32_t seq = 10;
    const std::vector<uint8_t> msg = {1, 2, 3, 4, 5};
    auto d = codec.encode(PacketType::FrameDone, 3, 42, msg, 1400, &seq);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].size(), kHeaderSize + msg.size() + kTagSize);
    EXPECT_EQ(seq, 11u);
    DecodeResult r = codec.decode(d[0].data(), d[0].size());
    ASSERT_TRUE(r.packet);
    EXPECT_EQ(r.packet->header.type, PacketType::FrameDone);
    EXPECT_EQ(r.packet->header.sender, 3);
    EXPECT_EQ(r.packet->header.frame, 42u);
    EXPECT_EQ(r.packet->header.sequence, 10u);
    EXPECT_EQ(r.packet->payload, msg);
    // Header fields are little-endian at the documented offsets.
    EXPECT_EQ(d[0][0], 0x43);  // 'C'
    EXPECT_EQ(d[0][1], 0x55);  // 'U'
    EXPECT_EQ(d[0][4], kProtocolVersion);
    EXPECT_EQ(d[0][8], 77);
    EXPECT_EQ(d[0][40], 42);  // frame, after sequence (20), session (24) and to_session (32)
}

TEST(Packet, SessionsTravelInTheSignedHeader) {
    PacketCodec codec(77, key_of(1), 0x1122334455667788ull);
    uint32_t seq = 0;
    auto d = codec.encode(PacketType::Hello, 3, 0, {1, 2}, 1400, &seq, 0x0A0B0C0D0E0F1011ull)[0];
    auto r = codec.decode(d.data(), d.size());
    ASSERT_TRUE(r.packet);
    EXPECT_EQ(r.packet->header.session, 0x1122334455667788ull);
    EXPECT_EQ(r.packet->header.to_session, 0x0A0B0C0D0E0F1011ull);
    EXPECT_EQ(d[24], 0x88);
    EXPECT_EQ(d[32], 0x11);
    // Neither can be changed without the key.
    d[24] ^= 1;
    EXPECT_EQ(codec.decode(d.data(), d.size()).reason, RejectReason::BadAuth);
    EXPECT_NE(new_session_nonce(), new_session_nonce());
    EXPECT_NE(new_session_nonce(), 0u);
}

TEST(Packet, FragmentedSnapshotReassemblesInAnyOrder) {
    PacketCodec codec(5, key_of(2));
    const Snapshot s = sample_snapshot(300);
    const auto msg = encode_snapshot(s);
    uint32_t seq = 0;
    auto frags = codec.encode(PacketType::Snapshot, kMasterSender, s.frame, msg, 512, &seq);
    ASSERT_GT(frags.size(), 20u);
    for (const auto& f : frags) EXPECT_LE(f.size(), 512u);
    std::mt19937 rng(7);
    std::shuffle(frags.begin(), frags.end(), rng);
    Reassembler re;
    std::optional<Message> done;
    for (size_t i = 0; i < frags.size(); ++i) {
        auto r = codec.decode(frags[i].data(), frags[i].size());
        ASSERT_TRUE(r.packet) << reject_reason_name(r.reason);
        auto m = re.add(std::move(*r.packet));
        if (i + 1 < frags.size())
            EXPECT_FALSE(m);
        else
            done = m;
    }
    ASSERT_TRUE(done);
    EXPECT_EQ(done->frame, s.frame);
    EXPECT_EQ(decode_snapshot(done->payload.data(), done->payload.size()), s);
}

TEST(Packet, MissingFragmentNeverCompletesAndIsCountedWhenEvicted) {
    PacketCodec codec(5, key_of(2));
    Reassembler re(2);
    uint32_t seq = 0;
    auto feed = [&](uint64_t frame, bool drop_one) {
        auto frags =
            codec.encode(PacketType::Snapshot, kMasterSender, frame, encode_snapshot(sample_snapshot(60)), 400, &seq);
        std::optional<Message> out;
        for (size_t i = 0; i < frags.size(); ++i) {
            if (drop_one && i == 1) continue;
            auto r = codec.decode(frags[i].data(), frags[i].size());
            if (auto m = re.add(std::move(*r.packet))) out = m;
        }
        return out;
    };
    EXPECT_FALSE(feed(1, true));
    EXPECT_FALSE(feed(2, true));
    EXPECT_EQ(re.incomplete_dropped(), 0u);
    EXPECT_TRUE(feed(3, false));  // a whole later frame still arrives: a lost snapshot costs one frame
    EXPECT_FALSE(feed(4, true));
    EXPECT_EQ(re.incomplete_dropped(), 1u);  // the oldest pending one was given up
    // A duplicate fragment is counted, not used twice.
    auto frags = codec.encode(PacketType::Snapshot, kMasterSender, 9, encode_snapshot(sample_snapshot(60)), 400, &seq);
    auto a = codec.decode(frags[0].data(), frags[0].size());
    auto b = codec.decode(frags[0].data(), frags[0].size());
    re.add(std::move(*a.packet));
    re.add(std::move(*b.packet));
    EXPECT_EQ(re.duplicates(), 1u);
}

TEST(Packet, BadDatagramsAreRejectedForTheRightReason) {
    PacketCodec codec(9, key_of(3));
    uint32_t seq = 0;
    const auto good =
        codec.encode(PacketType::Snapshot, kMasterSender, 1, encode_snapshot(sample_snapshot(2)), 1400, &seq)[0];
    ASSERT_TRUE(codec.decode(good.data(), good.size()).packet);
    auto reason = [&](const std::vector<uint8_t>& d) {
        auto r = codec.decode(d.data(), d.size());
        EXPECT_FALSE(r.packet);
        return r.reason;
    };
    auto corrupted = good;
    corrupted[kHeaderSize + 10] ^= 0x40;
    EXPECT_EQ(reason(corrupted), RejectReason::BadAuth);
    auto tag_flip = good;
    tag_flip.back() ^= 1;
    EXPECT_EQ(reason(tag_flip), RejectReason::BadAuth);
    auto truncated = good;
    truncated.resize(good.size() - 5);
    EXPECT_EQ(reason(truncated), RejectReason::BadLength);
    EXPECT_EQ(reason(std::vector<uint8_t>(good.begin(), good.begin() + 20)), RejectReason::BadLength);
    auto version = good;
    version[4] = 1;  // a version-1 node on the same network
    EXPECT_EQ(reason(version), RejectReason::BadVersion);
    auto magic = good;
    magic[0] = 'X';
    EXPECT_EQ(reason(magic), RejectReason::BadMagic);
    PacketCodec other_cluster(10, key_of(3));
    uint32_t s2 = 0;
    auto oc = other_cluster.encode(PacketType::Snapshot, kMasterSender, 1, {1, 2, 3}, 1400, &s2)[0];
    EXPECT_EQ(reason(oc), RejectReason::WrongCluster);
    PacketCodec other_key(9, key_of(4));
    auto ok = other_key.encode(PacketType::Snapshot, kMasterSender, 1, {1, 2, 3}, 1400, &s2)[0];
    EXPECT_EQ(reason(ok), RejectReason::BadAuth);
    // Authentic but inconsistent fragment fields.
    std::vector<uint8_t> raw(kHeaderSize + 4);
    ByteWriter w(raw);
    raw.clear();
    w.u32(kMagic);
    w.u16(kProtocolVersion);
    w.u8(1);
    w.u8(0);
    w.u32(9);
    w.u16(kMasterSender);
    w.u16(5);
    w.u16(3);  // fragment 5 of 3
    w.u16(0);
    w.u32(0);
    w.u64(7);
    w.u64(0);
    w.u64(1);
    w.u32(4);
    w.u32(0);
    w.u32(4);
    w.u32(0xDEADBEEF);
    AuthKey k = key_of(3);
    uint8_t tag[kTagSize];
    crypto_auth_hmacsha256(tag, raw.data(), raw.size(), k.data());
    w.bytes(tag, kTagSize);
    EXPECT_EQ(reason(raw), RejectReason::BadFragment);
}

TEST(Reports, RoundTripAndRefuseGarbage) {
    FrameReport r;
    r.channel = 3;
    r.frame = 99;
    r.snapshot_hash = "0123456789abcdef";
    r.render_ms = 12.5f;
    r.write_ms = 1.25f;
    r.packets_rejected = 4;
    r.snapshots_missed = 2;
    r.snapshot_received_ns = 123456789;
    FrameReport d = decode_frame_report(encode_frame_report(r));
    EXPECT_EQ(d.channel, 3);
    EXPECT_EQ(d.frame, 99u);
    EXPECT_EQ(d.snapshot_hash, r.snapshot_hash);
    EXPECT_EQ(d.render_ms, 12.5f);
    EXPECT_EQ(d.snapshot_received_ns, 123456789u);
    EXPECT_TRUE(d.glare.empty());
    auto bytes = encode_frame_report(r);
    bytes[10] = '!';
    EXPECT_THROW(decode_frame_report(bytes), WireError);

    // Glare measurements travel with the report, float for float.
    GlareMeasurement m;
    m.body = 0;
    m.frame = 98;
    m.total_sr = 6.8e-5f;
    for (int i = 0; i < GlareMeasurement::kWedges; ++i) m.visible_sr[i] = 2e-6f * static_cast<float>(i);
    r.glare = {m};
    d = decode_frame_report(encode_frame_report(r));
    ASSERT_EQ(d.glare.size(), 1u);
    EXPECT_EQ(d.glare[0].frame, 98u);
    EXPECT_EQ(d.glare[0].total_sr, m.total_sr);
    EXPECT_EQ(d.glare[0].visible_sr[7], m.visible_sr[7]);
    // More visible than total, or negative, is refused.
    r.glare[0].visible_sr[7] = 1.0f;
    EXPECT_THROW(decode_frame_report(encode_frame_report(r)), WireError);
    r.glare[0].visible_sr[7] = -1e-6f;
    EXPECT_THROW(decode_frame_report(encode_frame_report(r)), WireError);

    HelloMessage h{7, 4242, true, 17};
    HelloMessage hd = decode_hello(encode_hello(h));
    EXPECT_EQ(hd.channel, 7);
    EXPECT_EQ(hd.process_id, 4242u);
    EXPECT_TRUE(hd.has_frame);
    EXPECT_EQ(hd.last_frame, 17u);
    EXPECT_THROW(decode_hello({1, 2, 3}), WireError);
    auto bad_flag = encode_hello(h);
    bad_flag[6] = 2;
    EXPECT_THROW(decode_hello(bad_flag), WireError);
    const WelcomeMessage w = decode_welcome(encode_welcome({3, 99}));
    EXPECT_EQ(w.channel, 3);
    EXPECT_EQ(w.frame, 99u);
    EXPECT_THROW(decode_welcome({1}), WireError);
}

TEST(KeyFile, ReadsHexAndNamesBadFiles) {
    const std::string dir = std::string(CUPOLA_TEST_TMP) + "/keyfile";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    {
        std::ofstream(dir + "/good.key") << "00112233445566778899aabbccddeeff\n00112233445566778899AABBCCDDEEFF\n";
        std::ofstream(dir + "/short.key") << "abcd\n";
        std::ofstream(dir + "/bad.key") << std::string(63, 'a') << "g";
    }
    AuthKey k = load_key_file(dir + "/good.key");
    EXPECT_EQ(k[0], 0x00);
    EXPECT_EQ(k[15], 0xFF);
    EXPECT_EQ(k[31], 0xFF);
    for (const char* f : {"/short.key", "/bad.key", "/missing.key"}) {
        try {
            load_key_file(dir + f);
            FAIL() << f;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(f + 1), std::string::npos) << e.what();
        }
    }
}

TEST(KeyFile, AKeyEveryUserCanReadIsAWarningOrInStrictModeAnError) {
    const std::string dir = std::string(CUPOLA_TEST_TMP) + "/keyfile_mode";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string path = dir + "/cluster.key";
    std::ofstream(path) << std::string(64, 'a') << "\n";
    namespace fs = std::filesystem;
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
    EXPECT_NO_THROW(load_key_file(path, true));
    fs::permissions(path, fs::perms::owner_read | fs::perms::group_read, fs::perm_options::replace);
    EXPECT_NO_THROW(load_key_file(path, true));  // a group of render nodes may share it
    fs::permissions(path, fs::perms::owner_read | fs::perms::others_read, fs::perm_options::replace);
    EXPECT_NO_THROW(load_key_file(path, false));  // warning only
    try {
        load_key_file(path, true);
        FAIL() << "a world-readable key was accepted in strict mode";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("mode 404"), std::string::npos) << e.what();
    }
}

// --- Real sockets ---------------------------------------------------------------------------

namespace {
ClusterConfig socket_config(Transport t, uint16_t base_port, int channels) {
    ClusterConfig c;
    c.cluster_id = 31337;
    c.network.transport = t;
    c.network.multicast_group = "239.255.76." + std::to_string(100 + base_port % 100);
    c.network.snapshot_port = base_port;
    c.network.report_port = static_cast<uint16_t>(base_port + 1);
    c.network.max_datagram_bytes = 600;
    for (int i = 0; i < channels; ++i) {
        ChannelConfig ch;
        ch.id = i;
        ch.name = "c" + std::to_string(i);
        ch.unicast_address = "127.0.0.1:" + std::to_string(base_port + 10 + i);
        c.channels.push_back(ch);
    }
    return c;
}

void expect_every_slave_receives(Transport t, uint16_t port) {
    ClusterConfig cfg = socket_config(t, port, 2);
    const AuthKey key = key_of(5);
    std::vector<WireEndpoint> slaves;
    for (const auto& ch : cfg.channels) slaves.push_back(open_slave_endpoint(cfg, ch, key, new_session_nonce()));
    WireEndpoint master = open_master_endpoint(cfg, key, new_session_nonce());
    ASSERT_TRUE(test::handshake(master, slaves, cfg));
    const Snapshot s = sample_snapshot(40);  // ~3 KB: several fragments at 600 bytes
    master.send(PacketType::Snapshot, s.frame, encode_snapshot(s), snapshot_destinations(cfg));
    for (auto& sl : slaves) {
        auto m = sl.receive(2000);
        ASSERT_TRUE(m) << "slave got nothing";
        EXPECT_EQ(m->message.type, PacketType::Snapshot);
        EXPECT_EQ(decode_snapshot(m->message.payload.data(), m->message.payload.size()), s);
        // The report goes back to the master.
        FrameReport rep;
        rep.channel = static_cast<uint16_t>(&sl - slaves.data());
        rep.frame = s.frame;
        rep.snapshot_hash = snapshot_hash(m->message.payload);
        sl.send(PacketType::FrameDone, rep.frame, encode_frame_report(rep), {master_report_address(cfg)},
                master.session());
    }
    int reports = 0;
    while (auto m = master.receive(1000)) {
        EXPECT_EQ(m->message.type, PacketType::FrameDone);
        if (++reports == 2) break;
    }
    EXPECT_EQ(reports, 2);
}
}  // namespace

TEST(Sockets, MulticastReachesEverySlave) { expect_every_slave_receives(Transport::Multicast, 47710); }
TEST(Sockets, BroadcastReachesEverySlave) { expect_every_slave_receives(Transport::Broadcast, 47730); }
TEST(Sockets, UnicastReachesEverySlave) { expect_every_slave_receives(Transport::Unicast, 47750); }

// A datagram read late carries how long it waited (the kernel's receive timestamp), so that a
// network duplicate read by a process that was busy rendering is still taken for a duplicate.
// Linux turns its receive stamps on for the whole machine a moment after the first socket asks
// (a deferred switch); a datagram that arrives before then is stamped when read. So a first
// datagram warms the switch up before the one that is measured.
TEST(Sockets, ADatagramReadLateKnowsHowLongItWaited) {
    UdpSocket rx, tx;
    rx.bind(make_address("127.0.0.1", 0));
    const uint8_t byte = 1;
    tx.send_to(make_address("127.0.0.1", rx.local_port()), &byte, 1);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_TRUE(rx.receive(1000));
    tx.send_to(make_address("127.0.0.1", rx.local_port()), &byte, 1);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const auto d = rx.receive(1000);
    ASSERT_TRUE(d);
    EXPECT_GE(d->queued_ns, 250'000'000u);
    EXPECT_LT(d->queued_ns, 60'000'000'000u);
}

TEST(Sockets, ADuplicateReadLongAfterItArrivedIsADuplicateNotAReplay) {
    ClusterConfig cfg = socket_config(Transport::Unicast, 47790, 1);
    const AuthKey key = key_of(8);
    WireEndpoint slave = open_slave_endpoint(cfg, cfg.channels[0], key, new_session_nonce());
    UdpSocket network;
    const sockaddr_in to = parse_host_port(cfg.channels[0].unicast_address);
    PacketCodec master(cfg.cluster_id, key, new_session_nonce());
    uint32_t seq = 0;
    auto send = [&](const std::vector<uint8_t>& d) { network.send_to(to, d.data(), d.size()); };
    send(master.encode(PacketType::Welcome, kMasterSender, 0, encode_welcome({0, 0}), 1400, &seq, slave.session())[0]);
    ASSERT_TRUE(slave.receive(2000));
    const auto g =
        master.encode(PacketType::Snapshot, kMasterSender, 1, encode_snapshot(sample_snapshot(1)), 1400, &seq)[0];
    send(g);
    ASSERT_TRUE(slave.receive(2000));  // the first copy, read at once
    send(g);                           // its duplicate arrives at once, and waits while the slave renders
    std::this_thread::sleep_for(std::chrono::milliseconds(700));  // past the 500 ms duplicate horizon
    EXPECT_FALSE(slave.receive(200));
    EXPECT_EQ(slave.counters().duplicates, 1u);
    EXPECT_EQ(slave.counters().rejected[static_cast<size_t>(RejectReason::Replayed)], 0u);
}

TEST(Sockets, BadDatagramsAreDroppedAndCountedNotFatal) {
    ClusterConfig cfg = socket_config(Transport::Unicast, 47770, 1);
    const AuthKey key = key_of(6);
    WireEndpoint slave = open_slave_endpoint(cfg, cfg.channels[0], key, new_session_nonce());
    UdpSocket attacker;
    const sockaddr_in to = parse_host_port(cfg.channels[0].unicast_address);
    const uint64_t master_session = new_session_nonce();
    PacketCodec good(cfg.cluster_id, key, master_session), wrong_key(cfg.cluster_id, key_of(7), master_session),
        wrong_cluster(1, key, master_session);
    uint32_t seq = 0;
    auto send = [&](const std::vector<uint8_t>& d) { attacker.send_to(to, d.data(), d.size()); };
    // The master's welcome establishes its session at the slave.
    send(good.encode(PacketType::Welcome, kMasterSender, 0, encode_welcome({0, 0}), 1400, &seq, slave.session())[0]);
    auto w = slave.receive(2000);
    ASSERT_TRUE(w && w->opened);
    const std::vector<uint8_t> msg = encode_snapshot(sample_snapshot(1));
    send({'n', 'o', 'p', 'e'});  // bad magic
    auto g = good.encode(PacketType::Snapshot, kMasterSender, 1, msg, 1400, &seq)[0];
    auto t = g;
    t.resize(t.size() - 1);
    send(t);  // truncated
    auto v = g;
    v[4] = 9;
    send(v);                                                                                 // version
    send(wrong_cluster.encode(PacketType::Snapshot, kMasterSender, 1, msg, 1400, &seq)[0]);  // cluster
    send(wrong_key.encode(PacketType::Snapshot, kMasterSender, 1, msg, 1400, &seq)[0]);      // key
    auto c = g;
    c[kHeaderSize] ^= 1;
    send(c);  // corrupted
    send(g);  // the good one
    auto m = slave.receive(2000);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->message.frame, 1u);
    const auto& cnt = slave.counters();
    EXPECT_EQ(cnt.rejected[static_cast<size_t>(RejectReason::BadMagic)], 1u);
    EXPECT_EQ(cnt.rejected[static_cast<size_t>(RejectReason::BadLength)], 1u);
    EXPECT_EQ(cnt.rejected[static_cast<size_t>(RejectReason::BadVersion)], 1u);
    EXPECT_EQ(cnt.rejected[static_cast<size_t>(RejectReason::WrongCluster)], 1u);
    EXPECT_EQ(cnt.rejected[static_cast<size_t>(RejectReason::BadAuth)], 2u);
    EXPECT_EQ(cnt.total_rejected(), 6u);
    EXPECT_NE(cnt.summary().find("authentication failed 2"), std::string::npos) << cnt.summary();
}

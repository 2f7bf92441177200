#include "wire/reports.hpp"

#include <cctype>
#include <cmath>

#include "wire/byte_io.hpp"

namespace cupola {

std::vector<uint8_t> encode_hello(const HelloMessage& m) {
    std::vector<uint8_t> out;
    ByteWriter w(out);
    w.u16(m.channel);
    w.u32(m.process_id);
    w.u8(m.has_frame ? 1 : 0);
    w.u64(m.last_frame);
    return out;
}

std::vector<uint8_t> encode_welcome(const WelcomeMessage& m) {
    std::vector<uint8_t> out;
    ByteWriter w(out);
    w.u16(m.channel);
    w.u64(m.frame);
    return out;
}

WelcomeMessage decode_welcome(const std::vector<uint8_t>& p) {
    ByteReader r(p.data(), p.size());
    WelcomeMessage m;
    m.channel = r.u16("welcome.channel");
    m.frame = r.u64("welcome.frame");
    if (r.remaining()) throw WireError("unexpected bytes after welcome");
    return m;
}

HelloMessage decode_hello(const std::vector<uint8_t>& p) {
    ByteReader r(p.data(), p.size());
    HelloMessage m;
    m.channel = r.u16("hello.channel");
    m.process_id = r.u32("hello.process_id");
    const uint8_t has = r.u8("hello.has_frame");
    if (has > 1) throw WireError("hello.has_frame must be 0 or 1");
    m.has_frame = has == 1;
    m.last_frame = r.u64("hello.last_frame");
    if (r.remaining()) throw WireError("unexpected bytes after hello");
    return m;
}

std::vector<uint8_t> encode_frame_report(const FrameReport& rep) {
    std::vector<uint8_t> out;
    ByteWriter w(out);
    w.u16(rep.channel);
    w.u64(rep.frame);
    std::string h = rep.snapshot_hash;
    h.resize(16, '0');
    w.bytes(reinterpret_cast<const uint8_t*>(h.data()), 16);
    w.f32(rep.render_ms);
    w.f32(rep.write_ms);
    w.u64(rep.packets_rejected);
    w.u64(rep.snapshots_missed);
    w.u64(rep.snapshot_received_ns);
    w.u16(static_cast<uint16_t>(rep.glare.size()));
    for (const auto& g : rep.glare) {
        w.u16(g.body);
        w.u32(g.star);
        w.u64(g.frame);
        w.f32(g.total_sr);
        for (float v : g.visible_sr) w.f32(v);
    }
    if (rep.presentation) {
        const PresentTiming& t = *rep.presentation;
        w.u64(t.ready_ns);
        w.u8(t.has_present ? 1 : 0);
        w.u64(t.presented_frame);
        w.u64(t.present_ns);
    }
    return out;
}

namespace {

PresentTiming read_present_timing(ByteReader& r) {
    PresentTiming t;
    t.ready_ns = r.u64("report.ready_ns");
    const uint8_t has = r.u8("report.has_present");
    if (has > 1) throw WireError("report.has_present must be 0 or 1");
    t.has_present = has == 1;
    t.presented_frame = r.u64("report.presented_frame");
    t.present_ns = r.u64("report.present_ns");
    if (!t.has_present && (t.presented_frame != 0 || t.present_ns != 0))
        throw WireError("report.presented_frame and present_ns must be 0 without a present");
    return t;
}

}  // namespace

std::vector<uint8_t> encode_present(const PresentMessage& m) {
    std::vector<uint8_t> out;
    ByteWriter w(out);
    w.u64(m.frame);
    return out;
}

PresentMessage decode_present(const std::vector<uint8_t>& p) {
    ByteReader r(p.data(), p.size());
    PresentMessage m;
    m.frame = r.u64("present.frame");
    if (r.remaining()) throw WireError("unexpected bytes after present");
    return m;
}

FrameReport decode_frame_report(const std::vector<uint8_t>& p) {
    ByteReader r(p.data(), p.size());
    FrameReport rep;
    rep.channel = r.u16("report.channel");
    rep.frame = r.u64("report.frame");
    rep.snapshot_hash.resize(16);
    for (auto& c : rep.snapshot_hash) {
        c = static_cast<char>(r.u8("report.snapshot_hash"));
        if (!std::isxdigit(static_cast<unsigned char>(c))) throw WireError("report.snapshot_hash is not hexadecimal");
    }
    rep.render_ms = r.f32("report.render_ms");
    rep.write_ms = r.f32("report.write_ms");
    if (!std::isfinite(rep.render_ms) || !std::isfinite(rep.write_ms)) throw WireError("report timings not finite");
    rep.packets_rejected = r.u64("report.packets_rejected");
    rep.snapshots_missed = r.u64("report.snapshots_missed");
    rep.snapshot_received_ns = r.u64("report.snapshot_received_ns");
    const uint16_t n = r.u16("report.glare_count");
    if (n > 64) throw WireError("report.glare_count " + std::to_string(n) + " exceeds 64");
    rep.glare.resize(n);
    for (auto& g : rep.glare) {
        g.body = r.u16("report.glare.body");
        g.star = r.u32("report.glare.star");
        g.frame = r.u64("report.glare.frame");
        g.total_sr = r.f32("report.glare.total_sr");
        bool ok = std::isfinite(g.total_sr) && g.total_sr >= 0.0f;
        for (float& v : g.visible_sr) {
            v = r.f32("report.glare.visible_sr");
            ok = ok && std::isfinite(v) && v >= 0.0f;
        }
        if (!ok) throw WireError("report.glare solid angles must be finite and non-negative");
        if (g.visible_total_sr() > g.total_sr * 1.0001f + 1e-12f)
            throw WireError("report.glare visible solid angle exceeds the total");
    }
    if (r.remaining()) rep.presentation = read_present_timing(r);
    if (r.remaining()) throw WireError("unexpected bytes after frame report");
    return rep;
}

}  // namespace cupola

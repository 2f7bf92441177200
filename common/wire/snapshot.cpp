#include "wire/snapshot.hpp"

#include <sodium.h>

#include <cmath>
#include <cstdio>

#include "wire/byte_io.hpp"

namespace cupola {

namespace {
constexpr size_t kMaxBodies = 4096;
constexpr size_t kMaxAggregates = 65536;

void put_dvec3(ByteWriter& w, const glm::dvec3& v) {
    w.f64(v.x);
    w.f64(v.y);
    w.f64(v.z);
}
void put_dquat(ByteWriter& w, const glm::dquat& q) {
    w.f64(q.w);
    w.f64(q.x);
    w.f64(q.y);
    w.f64(q.z);
}
double finite(ByteReader& r, const char* field) {
    double d = r.f64(field);
    if (!std::isfinite(d)) throw WireError(std::string("non-finite value in field '") + field + "'");
    return d;
}
glm::dvec3 get_dvec3(ByteReader& r, const char* field) {
    glm::dvec3 v;
    v.x = finite(r, field);
    v.y = finite(r, field);
    v.z = finite(r, field);
    return v;
}
glm::dquat get_dquat(ByteReader& r, const char* field) {
    glm::dquat q;
    q.w = finite(r, field);
    q.x = finite(r, field);
    q.y = finite(r, field);
    q.z = finite(r, field);
    double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (std::abs(n - 1.0) > 1e-6) throw WireError(std::string("field '") + field + "' is not a unit quaternion");
    return q;
}
}  // namespace

std::vector<uint8_t> encode_snapshot(const Snapshot& s) {
    std::vector<uint8_t> out;
    out.reserve(96 + s.bodies.size() * 58 + s.aggregates.size() * 12);
    ByteWriter w(out);
    w.u64(s.frame);
    w.f64(s.sim_time_s);
    put_dvec3(w, s.camera_position_m);
    put_dquat(w, s.camera_orientation);
    w.f32(s.settings.exposure);
    w.f32(s.settings.star_magnitude_limit);
    w.u32(s.settings.flags);
    w.u32(static_cast<uint32_t>(s.bodies.size()));
    for (const auto& b : s.bodies) {
        w.u16(b.id);
        put_dvec3(w, b.position_m);
        put_dquat(w, b.orientation);
    }
    w.u32(static_cast<uint32_t>(s.aggregates.size()));
    for (const auto& a : s.aggregates) {
        w.u16(a.key);
        w.u16(a.subject);
        w.f64(a.value);
    }
    return out;
}

Snapshot decode_snapshot(const uint8_t* data, size_t size) {
    ByteReader r(data, size);
    Snapshot s;
    s.frame = r.u64("frame");
    s.sim_time_s = finite(r, "sim_time_s");
    s.camera_position_m = get_dvec3(r, "camera_position_m");
    s.camera_orientation = get_dquat(r, "camera_orientation");
    s.settings.exposure = r.f32("settings.exposure");
    s.settings.star_magnitude_limit = r.f32("settings.star_magnitude_limit");
    if (!std::isfinite(s.settings.exposure) || !(s.settings.exposure > 0.0f))
        throw WireError("field 'settings.exposure' must be positive and finite");
    if (!std::isfinite(s.settings.star_magnitude_limit))
        throw WireError("field 'settings.star_magnitude_limit' is not finite");
    s.settings.flags = r.u32("settings.flags");
    uint32_t nb = r.u32("body_count");
    if (nb > kMaxBodies) throw WireError("body_count " + std::to_string(nb) + " exceeds " + std::to_string(kMaxBodies));
    s.bodies.resize(nb);
    for (auto& b : s.bodies) {
        b.id = r.u16("bodies.id");
        b.position_m = get_dvec3(r, "bodies.position_m");
        b.orientation = get_dquat(r, "bodies.orientation");
    }
    uint32_t na = r.u32("aggregate_count");
    if (na > kMaxAggregates) throw WireError("aggregate_count " + std::to_string(na) + " is too large");
    s.aggregates.resize(na);
    for (auto& a : s.aggregates) {
        a.key = r.u16("aggregates.key");
        a.subject = r.u16("aggregates.subject");
        a.value = finite(r, "aggregates.value");
    }
    if (r.remaining() != 0)
        throw WireError(std::to_string(r.remaining()) + " unexpected bytes after the snapshot's last field");
    return s;
}

std::string snapshot_hash(const std::vector<uint8_t>& encoded) {
    unsigned char h[8];
    crypto_generichash(h, sizeof h, encoded.data(), encoded.size(), nullptr, 0);
    char hex[17];
    for (int i = 0; i < 8; ++i) std::snprintf(hex + 2 * i, 3, "%02x", h[i]);
    return std::string(hex, 16);
}

}  // namespace cupola

#include "wire/snapshot.hpp"

#include <sodium.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "wire/byte_io.hpp"

namespace cupola {

namespace {
constexpr size_t kMaxBodies = 4096;
constexpr size_t kMaxGlareSources = 64;

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
void put_vec3(ByteWriter& w, const glm::vec3& v) {
    w.f32(v.x);
    w.f32(v.y);
    w.f32(v.z);
}
float finite_f(ByteReader& r, const char* field) {
    float f = r.f32(field);
    if (!std::isfinite(f)) throw WireError(std::string("non-finite value in field '") + field + "'");
    return f;
}
glm::vec3 get_vec3(ByteReader& r, const char* field) {
    glm::vec3 v;
    v.x = finite_f(r, field);
    v.y = finite_f(r, field);
    v.z = finite_f(r, field);
    return v;
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

GlareSource get_glare_source(ByteReader& r) {
    GlareSource g;
    g.body = r.u16("glare.body");
    g.star = r.u32("glare.star");
    g.direction = get_vec3(r, "glare.direction");
    if (std::abs(glm::length(g.direction) - 1.0f) > 1e-4f)
        throw WireError("field 'glare.direction' is not a unit vector");
    g.angular_radius = finite_f(r, "glare.angular_radius");
    if (g.angular_radius < 0.0f || g.angular_radius > 1.6f)
        throw WireError("field 'glare.angular_radius' must lie in [0, pi/2]");
    g.irradiance = get_vec3(r, "glare.irradiance");
    if (glm::any(glm::lessThan(g.irradiance, glm::vec3(0.0f))))
        throw WireError("field 'glare.irradiance' must not be negative");
    g.visible_fraction = finite_f(r, "glare.visible_fraction");
    if (g.visible_fraction < 0.0f || g.visible_fraction > 1.0f)
        throw WireError("field 'glare.visible_fraction' must lie in [0, 1]");
    g.centroid_offset = get_vec3(r, "glare.centroid_offset");
    const uint8_t origin = r.u8("glare.origin");
    if (origin > static_cast<uint8_t>(GlareOrigin::Analytic)) throw WireError("field 'glare.origin' is unknown");
    g.origin = static_cast<GlareOrigin>(origin);
    g.measured_frame = r.u64("glare.measured_frame");
    return g;
}

HeadPose get_head_pose(ByteReader& r) {
    HeadPose h;
    const uint8_t source = r.u8("head.source");
    if (source >= kHeadSourceCount) throw WireError("field 'head.source' is unknown");
    h.source = static_cast<HeadSource>(source);
    h.position_m = get_dvec3(r, "head.position_m");
    h.orientation = get_dquat(r, "head.orientation");
    return h;
}
}  // namespace

std::vector<uint8_t> encode_snapshot(const Snapshot& s) {
    std::vector<uint8_t> out;
    out.reserve(112 + s.bodies.size() * 58 + s.glare.size() * 59);
    ByteWriter w(out);
    w.u64(s.frame);
    w.f64(s.sim_time_s);
    put_dvec3(w, s.camera_position_m);
    put_dquat(w, s.camera_orientation);
    w.f32(s.settings.exposure);
    w.f32(s.settings.star_magnitude_limit);
    w.u32(s.settings.flags);
    w.f32(s.settings.glare_phase);
    w.f32(s.settings.tone_white);
    w.f32(s.settings.adapted_cd_m2);
    w.f32(s.settings.twinkle_time_s);
    w.f32(s.settings.night_sky_cd_m2);
    for (float a : s.settings.overlay_alpha) w.f32(a);
    w.u32(static_cast<uint32_t>(s.bodies.size()));
    for (const auto& b : s.bodies) {
        w.u16(b.id);
        put_dvec3(w, b.position_m);
        put_dquat(w, b.orientation);
    }
    w.u32(static_cast<uint32_t>(s.glare.size()));
    for (const auto& g : s.glare) {
        w.u16(g.body);
        w.u32(g.star);
        put_vec3(w, g.direction);
        w.f32(g.angular_radius);
        put_vec3(w, g.irradiance);
        w.f32(g.visible_fraction);
        put_vec3(w, g.centroid_offset);
        w.u8(static_cast<uint8_t>(g.origin));
        w.u64(g.measured_frame);
    }
    w.u8(static_cast<uint8_t>(s.head.source));
    put_dvec3(w, s.head.position_m);
    put_dquat(w, s.head.orientation);
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
    s.settings.glare_phase = finite_f(r, "settings.glare_phase");
    s.settings.tone_white = finite_f(r, "settings.tone_white");
    if (s.settings.tone_white < 0.0f) throw WireError("field 'settings.tone_white' must not be negative");
    s.settings.adapted_cd_m2 = finite_f(r, "settings.adapted_cd_m2");
    if (s.settings.adapted_cd_m2 < 0.0f) throw WireError("field 'settings.adapted_cd_m2' must not be negative");
    s.settings.twinkle_time_s = finite_f(r, "settings.twinkle_time_s");
    s.settings.night_sky_cd_m2 = finite_f(r, "settings.night_sky_cd_m2");
    if (s.settings.night_sky_cd_m2 < 0.0f) throw WireError("field 'settings.night_sky_cd_m2' must not be negative");
    for (float& a : s.settings.overlay_alpha) {
        a = finite_f(r, "settings.overlay_alpha");
        if (a < 0.0f || a > 1.0f) throw WireError("field 'settings.overlay_alpha' must be in [0, 1]");
    }
    uint32_t nb = r.u32("body_count");
    if (nb > kMaxBodies) throw WireError("body_count " + std::to_string(nb) + " exceeds " + std::to_string(kMaxBodies));
    s.bodies.resize(nb);
    for (auto& b : s.bodies) {
        b.id = r.u16("bodies.id");
        b.position_m = get_dvec3(r, "bodies.position_m");
        b.orientation = get_dquat(r, "bodies.orientation");
    }
    uint32_t ng = r.u32("glare_count");
    if (ng > kMaxGlareSources)
        throw WireError("glare_count " + std::to_string(ng) + " exceeds " + std::to_string(kMaxGlareSources));
    s.glare.resize(ng);
    for (auto& g : s.glare) g = get_glare_source(r);
    s.head = get_head_pose(r);
    if (r.remaining() != 0)
        throw WireError(std::to_string(r.remaining()) + " unexpected bytes after the snapshot's last field");
    return s;
}

const std::vector<std::string>& alignment_pattern_names() {
    static const std::vector<std::string> names{"off", "grid", "white", "black"};
    return names;
}

const char* alignment_pattern_name(AlignmentPattern p) {
    return alignment_pattern_names().at(static_cast<size_t>(p)).c_str();
}

AlignmentPattern alignment_pattern_from_name(const std::string& name) {
    const auto& n = alignment_pattern_names();
    for (size_t i = 0; i < n.size(); ++i)
        if (n[i] == name) return static_cast<AlignmentPattern>(i);
    throw std::invalid_argument("unknown alignment pattern \"" + name + "\" (grid, white, black or off)");
}

const std::vector<std::string>& twinkle_mode_names() {
    static const std::vector<std::string> names{"off", "on", "forced"};
    return names;
}

TwinkleMode twinkle_mode_from_name(const std::string& name) {
    const auto& n = twinkle_mode_names();
    for (size_t i = 0; i < n.size(); ++i)
        if (n[i] == name) return static_cast<TwinkleMode>(i);
    throw std::invalid_argument("unknown twinkle mode \"" + name + "\" (on, off or forced)");
}

std::string snapshot_hash(const std::vector<uint8_t>& encoded) {
    unsigned char h[8];
    crypto_generichash(h, sizeof h, encoded.data(), encoded.size(), nullptr, 0);
    char hex[17];
    for (int i = 0; i < 8; ++i) std::snprintf(hex + 2 * i, 3, "%02x", h[i]);
    return std::string(hex, 16);
}

}  // namespace cupola

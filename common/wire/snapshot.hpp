#pragma once
// The master's state for one frame, sent whole every frame (a lost snapshot costs one frame).
// All positions are double, in metres, in the world frame (ICRF-aligned equatorial axes, origin
// at the Sun); orientations map body/camera frames to the world frame.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "overlay/overlay_kind.hpp"
#include "tracking/head_pose.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cupola {

struct BodyState {
    uint16_t id = 0;  // index into SceneConfig::bodies
    glm::dvec3 position_m{0.0};
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
    bool operator==(const BodyState&) const = default;
};

// The alignment pattern every channel draws instead of the scene (docs/ALIGNMENT.md): one value
// for the whole cluster, decided by the master once per frame.
enum class AlignmentPattern : uint8_t {
    Off = 0,    // the scene
    Grid = 1,   // azimuth/elevation grid in dome coordinates, channel label, overlaps tinted
    White = 2,  // a uniform white field (blend checks)
    Black = 3,  // a black field (black level)
};

struct RenderSettings {
    float exposure = 1.0f;
    float star_magnitude_limit = 6.5f;
    uint32_t flags = 0;  // effect switches (bits 0..2: eclipse shadow mode; 3..4: alignment pattern; 5..6: twinkle; 7:
                         // night vision; 8: acuity blur; 7: night vision)
    float glare_phase = 0.0f;  // glare animation phase: one value for the whole cluster
    // The display curve's white: the exposed luminance shown as white (shaders/shared/tone_curve.glsl);
    // 0: no curve (a fixed exposure). And the eye's adapted luminance, cd/m^2 (0: not metered).
    // Both decided once per frame by the master (common/exposure/eye_adaptation.hpp).
    float tone_white = 0.0f;
    float adapted_cd_m2 = 0.0f;
    // The stars' twinkle clock, seconds of show time (wraps at 4096 s): one value for the whole
    // cluster, so every channel twinkles alike (shaders/shared/star_twinkle.glsl).
    float twinkle_time_s = 0.0f;
    // The night sky's own zenith luminance, cd/m^2 (airglow and light pollution; 0: none): the
    // scene's, a show's or the presenter's (shaders/shared/night_sky.glsl).
    float night_sky_cd_m2 = 0.0f;
    // Each overlay's opacity, 0..1, in OverlayKind's order (common/overlay/overlay_kind.hpp): the
    // master fades them in and out, one value for the whole cluster.
    std::array<float, kOverlayCount> overlay_alpha{};
    bool operator==(const RenderSettings&) const = default;
};

// Where a glare source's visible fraction came from.
enum class GlareOrigin : uint8_t {
    Measured = 0,  // the channels' occlusion queries of the previous frame, summed by the master
    Analytic = 1,  // spherical occluders (a report was missing, or no channel sees the source)
};

// A source of glare (the Sun, a bright planet or star) as the master shares it with every
// channel: where it is, how bright, and how much of it the whole cluster saw. Every channel
// draws the glare from these values, including channels where the source is out of view.
struct GlareSource {
    static constexpr uint16_t kCatalogStar = 0xFFFF;
    uint16_t body = kCatalogStar;            // scene body id, or kCatalogStar
    uint32_t star = 0;                       // catalogue index when body == kCatalogStar
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit, world frame, camera to the source's centre
    float angular_radius = 0.0f;             // radians (0: a point)
    glm::vec3 irradiance{0.0f};              // rgb, scene units x sr at the camera (after any atmosphere)
    float visible_fraction = 1.0f;           // cluster-wide
    glm::vec3 centroid_offset{0.0f};         // world frame, radians: centre -> centroid of the visible part
    GlareOrigin origin = GlareOrigin::Analytic;
    uint64_t measured_frame = 0;  // frame whose queries gave visible_fraction (when Measured)
    bool operator==(const GlareSource&) const = default;
    bool same_source(const GlareSource& o) const { return body == o.body && star == o.star; }
};

struct Snapshot {
    uint64_t frame = 0;
    double sim_time_s = 0.0;  // seconds since J2000.0 (TT)
    glm::dvec3 camera_position_m{0.0};
    glm::dquat camera_orientation{1.0, 0.0, 0.0, 0.0};
    std::vector<BodyState> bodies;
    RenderSettings settings;
    std::vector<GlareSource> glare;  // brightest first; empty when the scene has no glare
    // The viewer's head in the room (VR walls and CAVEs): channels given as screens are seen from
    // it. One pose per frame for the whole cluster (the master's HeadTracker).
    HeadPose head;

    bool operator==(const Snapshot&) const = default;
};

// RenderSettings::flags bits 3..4: the alignment pattern. Every value of the two bits is a
// pattern, so the snapshot's layout is unchanged and a node that ignores the bits draws the scene.
constexpr uint32_t kAlignmentPatternShift = 3;
constexpr uint32_t kAlignmentPatternMask = 0x3u << kAlignmentPatternShift;
inline AlignmentPattern alignment_pattern_of(uint32_t flags) {
    return static_cast<AlignmentPattern>((flags & kAlignmentPatternMask) >> kAlignmentPatternShift);
}
inline uint32_t with_alignment_pattern(uint32_t flags, AlignmentPattern p) {
    return (flags & ~kAlignmentPatternMask) | (static_cast<uint32_t>(p) << kAlignmentPatternShift);
}
// "off", "grid", "white", "black" (in AlignmentPattern's order).
const std::vector<std::string>& alignment_pattern_names();
const char* alignment_pattern_name(AlignmentPattern p);
// Throws std::invalid_argument naming the word and the choices.
AlignmentPattern alignment_pattern_from_name(const std::string& name);

// RenderSettings::flags bits 5..6: the stars' twinkling (shaders/shared/star_twinkle.glsl).
enum class TwinkleMode : uint8_t {
    Off = 0,     // steady stars
    On = 1,      // stars twinkle as the air above a camera inside an atmosphere makes them
    Forced = 2,  // twinkle also without air (a planetarium's choice), as at the zenith
};
constexpr uint32_t kTwinkleShift = 5;
constexpr uint32_t kTwinkleMask = 0x3u << kTwinkleShift;
inline TwinkleMode twinkle_mode_of(uint32_t flags) {
    const uint32_t v = (flags & kTwinkleMask) >> kTwinkleShift;
    return v > 2 ? TwinkleMode::Off : static_cast<TwinkleMode>(v);
}
inline uint32_t with_twinkle_mode(uint32_t flags, TwinkleMode m) {
    return (flags & ~kTwinkleMask) | (static_cast<uint32_t>(m) << kTwinkleShift);
}
// RenderSettings::flags bit 7: the display transform includes the eye's night vision at the
// snapshot's adapted luminance (shaders/shared/night_vision.glsl).
constexpr uint32_t kNightVisionBit = 0x1u << 7;
inline bool night_vision_of(uint32_t flags) { return (flags & kNightVisionBit) != 0; }
// RenderSettings::flags bit 8: with night vision, the display transform also blurs the sky as the
// eye's acuity falls at the adapted luminance (shaders/shared/night_acuity.glsl).
constexpr uint32_t kAcuityBlurBit = 0x1u << 8;
inline bool acuity_blur_of(uint32_t flags) { return (flags & kAcuityBlurBit) != 0; }

// "off", "on", "forced" (in TwinkleMode's order).
const std::vector<std::string>& twinkle_mode_names();
// Throws std::invalid_argument naming the word and the choices.
TwinkleMode twinkle_mode_from_name(const std::string& name);

std::vector<uint8_t> encode_snapshot(const Snapshot& s);
// Throws WireError naming the field when the payload is short, long or holds a non-finite value.
Snapshot decode_snapshot(const uint8_t* data, size_t size);

// A short, stable hash (hex, 16 digits) of the encoded snapshot: what a frame file records so
// that sync can be checked from the files alone.
std::string snapshot_hash(const std::vector<uint8_t>& encoded);

}  // namespace cupola

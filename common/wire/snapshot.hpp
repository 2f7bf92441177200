#pragma once
// The master's state for one frame, sent whole every frame (a lost snapshot costs one frame).
// All positions are double, in metres, in the world frame (ICRF-aligned equatorial axes, origin
// at the Sun); orientations map body/camera frames to the world frame.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

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

struct RenderSettings {
    float exposure = 1.0f;
    float star_magnitude_limit = 6.5f;
    uint32_t flags = 0;  // reserved for effect switches (atmosphere, shadows, glare)
    bool operator==(const RenderSettings&) const = default;
};

// A value the master aggregates from the channels' reports and shares with every channel
// (the glare issue puts per-body visibility here).
struct ClusterAggregate {
    uint16_t key = 0;
    uint16_t subject = 0;  // e.g. body id
    double value = 0.0;
    bool operator==(const ClusterAggregate&) const = default;
};

struct Snapshot {
    uint64_t frame = 0;
    double sim_time_s = 0.0;  // seconds since J2000.0 (TT)
    glm::dvec3 camera_position_m{0.0};
    glm::dquat camera_orientation{1.0, 0.0, 0.0, 0.0};
    std::vector<BodyState> bodies;
    RenderSettings settings;
    std::vector<ClusterAggregate> aggregates;

    bool operator==(const Snapshot&) const = default;
};

std::vector<uint8_t> encode_snapshot(const Snapshot& s);
// Throws WireError naming the field when the payload is short, long or holds a non-finite value.
Snapshot decode_snapshot(const uint8_t* data, size_t size);

// A short, stable hash (hex, 16 digits) of the encoded snapshot: what a frame file records so
// that sync can be checked from the files alone.
std::string snapshot_hash(const std::vector<uint8_t>& encoded);

}  // namespace cupola

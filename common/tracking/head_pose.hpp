#pragma once
// The viewer's head in the room of a VR wall or a CAVE, as the master decides it once per frame and
// carries it in the snapshot: every channel of a frame sees the scene from the same eyes.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>

namespace cupola {

// Where a frame's head pose came from.
enum class HeadSource : uint8_t {
    Default = 0,  // no tracking, or the tracker was lost for longer than its timeout: room.eye_m
    Tracked = 1,  // a tracker sample fresh for this frame
    Held = 2,     // the tracker is late: its last pose, until the timeout
    Control = 3,  // set by the presenter over the control channel
};
constexpr uint8_t kHeadSourceCount = 4;

struct HeadPose {
    glm::dvec3 position_m{0.0};                  // the point between the eyes, room frame
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // head -> room (the head looks along its -z, x to its right)
    HeadSource source = HeadSource::Default;
    bool operator==(const HeadPose&) const = default;
};

// "default", "tracked", "held", "control" (in HeadSource's order).
const char* head_source_name(HeadSource s);

}  // namespace cupola

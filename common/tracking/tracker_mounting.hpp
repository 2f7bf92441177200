#pragma once
// How a tracker's own room frame sits in Cupola's room frame (x right, y up, z toward the back,
// metres): its axes convention, where its origin is, and its unit (DTrack2: millimetres).
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

#include "tracking/dtrack_packet.hpp"
#include "tracking/head_pose.hpp"

namespace cupola {

enum class TrackerAxes {
    YUp,  // x right, y up, z toward the viewer (DTrack2's "powerwall" room calibration): Cupola's own
    ZUp,  // x right, y toward the front screen, z up (DTrack2's "normal" room calibration)
};

// "y_up", "z_up" (in TrackerAxes' order).
const std::vector<std::string>& tracker_axes_names();
// Throws std::invalid_argument naming the word and the choices.
TrackerAxes tracker_axes_from_name(const std::string& name);

struct TrackerMounting {
    TrackerAxes axes = TrackerAxes::YUp;
    glm::dvec3 origin_m{0.0};  // the tracker's origin in the room
};

// The tracker frame's axes in the room frame: room = rotation * tracker.
glm::dmat3 room_from_tracker(TrackerAxes axes);

// A tracked DTrack2 body as a head pose in the room (source Tracked). The body's own axes follow the
// tracker's convention (z_up: its y is where it looks, its z up), so that a body calibrated
// unturned looks to the front: the head looks along its -z in the room's convention.
HeadPose head_pose_from_dtrack(const DtrackBody& body, const TrackerMounting& mounting);

}  // namespace cupola

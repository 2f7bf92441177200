#include "tracking/tracker_mounting.hpp"

#include <stdexcept>

namespace cupola {

const std::vector<std::string>& tracker_axes_names() {
    static const std::vector<std::string> names = {"y_up", "z_up"};
    return names;
}

TrackerAxes tracker_axes_from_name(const std::string& name) {
    const auto& n = tracker_axes_names();
    for (size_t i = 0; i < n.size(); ++i)
        if (n[i] == name) return static_cast<TrackerAxes>(i);
    throw std::invalid_argument("'" + name + "' is not a tracker axes convention (y_up or z_up)");
}

glm::dmat3 room_from_tracker(TrackerAxes axes) {
    if (axes == TrackerAxes::YUp) return glm::dmat3(1.0);
    // Columns: the tracker's x, y and z in the room. Its y points to the front (room -z), its z up.
    return glm::dmat3(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(0.0, 1.0, 0.0));
}

HeadPose head_pose_from_dtrack(const DtrackBody& body, const TrackerMounting& mounting) {
    const glm::dmat3 to_room = room_from_tracker(mounting.axes);
    HeadPose p;
    p.position_m = mounting.origin_m + to_room * (body.position_mm * 1e-3);
    // The body's own axes follow the tracker's convention too (an unturned body looks to the front).
    p.orientation = glm::normalize(glm::quat_cast(to_room * body.rotation * glm::transpose(to_room)));
    p.source = HeadSource::Tracked;
    return p;
}

}  // namespace cupola

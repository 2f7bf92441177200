// libFuzzer target cupola-fuzz-dtrack: the A.R.T. DTrack2 ASCII parser (common/tracking/
// dtrack_packet) and the head pose made from it, under hostile datagrams. Checked invariants (a
// violation aborts, which libFuzzer reports): the parser returns a packet or throws DtrackError;
// a packet has its frame counter, at most kDtrackMaxBodies bodies with distinct ids, finite
// positions and rotation matrices; the head pose from any of its bodies is finite with a unit
// quaternion. ASan/UBSan turn memory errors and UB into crashes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "tracking/dtrack_packet.hpp"
#include "tracking/tracker_mounting.hpp"

using namespace cupola;

namespace {
[[noreturn]] void violated(const char* what) {
    std::fprintf(stderr, "invariant violated: %s\n", what);
    std::abort();
}

void check_pose(const HeadPose& p) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(p.position_m[i])) violated("a head position is not finite");
    const double n = glm::length(glm::dvec4(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z));
    if (!(std::abs(n - 1.0) < 1e-9)) violated("a head orientation is not a unit quaternion");
}

void check_packet(const DtrackPacket& p) {
    if (!p.frame) violated("a packet without its frame counter");
    if (p.bodies.size() > static_cast<size_t>(kDtrackMaxBodies)) violated("too many bodies");
    for (size_t i = 0; i < p.bodies.size(); ++i) {
        if (find_dtrack_body(p, p.bodies[i].id) != &p.bodies[i]) violated("a body id given twice");
        const glm::dmat3& r = p.bodies[i].rotation;
        if (!(std::abs(glm::determinant(r) - 1.0) < 1e-2)) violated("a rotation whose determinant is not 1");
        for (TrackerAxes axes : {TrackerAxes::YUp, TrackerAxes::ZUp})
            check_pose(head_pose_from_dtrack(p.bodies[i], TrackerMounting{axes, glm::dvec3(1.0, 0.0, -2.0)}));
    }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        check_packet(parse_dtrack_packet(std::string_view(reinterpret_cast<const char*>(data), size)));
    } catch (const DtrackError&) {}
    return 0;
}

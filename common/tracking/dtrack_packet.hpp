#pragma once
// One datagram of an A.R.T. DTrack2 tracking system's ASCII output (A.R.T. GmbH, "DTrack2 User
// Manual", Technical Appendix, "Output data, ASCII format"), as many CAVEs send it by UDP every
// measurement: lines ending in CR LF, each opened by its kind:
//
//   fr 21753                                   the measurement's frame counter
//   ts 39596.024831                            its timestamp (seconds since midnight UTC), optional
//   6dcal 2                                    how many 6DOF bodies are calibrated
//   6d 1 [0 1.000][326.8 -187.2 109.5 -160.47 -3.69 -7.09][b0 b1 b2 b3 b4 b5 b6 b7 b8]
//
// A 6d line counts the bodies tracked now, then gives each as [id quality][x y z eta theta phi]
// [rotation]: the id from 0, the position in millimetres in the tracker's room frame, three angles
// (ignored here: the matrix says the same without their singularities) and the body-to-room
// rotation matrix column by column (b0 b1 b2 is its first column). Lines of other kinds (3d, 6df2,
// gl, ...) are counted and skipped.
#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace cupola {

// A datagram that is not DTrack2 ASCII output: says the line, its kind and what was wrong.
struct DtrackError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct DtrackBody {
    int id = 0;
    double quality = 0.0;  // 0..1 as DTrack2 measures it
    glm::dvec3 position_mm{0.0};
    glm::dmat3 rotation{1.0};  // body -> tracker room, orthonormal (checked)
};

struct DtrackPacket {
    std::optional<uint64_t> frame;
    std::optional<double> timestamp_s;
    std::optional<int> calibrated_bodies;
    std::vector<DtrackBody> bodies;  // the 6d line's, in its order
    int skipped_lines = 0;           // lines of kinds not read here
};

constexpr size_t kDtrackMaxPacketBytes = 65536;
constexpr int kDtrackMaxBodies = 256;

// Parses a whole datagram. Throws DtrackError on anything that is not the format above: an empty
// or over-long datagram, a bad number, a count that does not match the bodies given, a block with
// the wrong number of values, a position or quality that is not finite, a matrix that is not a
// rotation (orthonormal to 1e-3, determinant +1), a body twice.
DtrackPacket parse_dtrack_packet(std::string_view text);

// The body with this id, if the packet tracks it.
const DtrackBody* find_dtrack_body(const DtrackPacket& p, int id);

}  // namespace cupola

#pragma once
// How an MPCDI package is read where the standard is ambiguous (VESA MPCDI v2.0 (2015); the
// choices and how each was checked: docs/MPCDI.md). Every switch has a default and can be set from
// its string form, so a config field or a `cupola-warp` flag can pass it.
#include <string>
#include <string_view>

#include "calibration/pfm_file.hpp"

namespace cupola {

enum class VOrigin { bottom, top };             // the file's v = 0 is the content's bottom | top edge
enum class WarpCoordinates { region, buffer };  // the file's (u, v) are region-local | buffer-global
enum class WarpDirection { forward, inverse };  // projector point -> content | content -> projector

struct MpcdiReading {
    PfmRows pfm_rows = PfmRows::bottom_first;               // "pfm_rows": bottom-first | top-first
    VOrigin v_origin = VOrigin::bottom;                     // "v_origin": bottom | top
    WarpCoordinates coordinates = WarpCoordinates::region;  // "coordinates": region | buffer
    WarpDirection warp_direction = WarpDirection::forward;  // "warp_direction": forward | inverse

    // Sets the switch `name` ("pfm_rows", "v_origin", "coordinates", "warp_direction") from its
    // string value; throws std::invalid_argument naming the switch and the values it takes.
    void set(std::string_view name, std::string_view value);
};

PfmRows parse_pfm_rows(std::string_view value);
VOrigin parse_v_origin(std::string_view value);
WarpCoordinates parse_warp_coordinates(std::string_view value);
WarpDirection parse_warp_direction(std::string_view value);

std::string to_string(PfmRows v);
std::string to_string(VOrigin v);
std::string to_string(WarpCoordinates v);
std::string to_string(WarpDirection v);

}  // namespace cupola

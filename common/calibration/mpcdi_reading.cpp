#include "calibration/mpcdi_reading.hpp"

#include <stdexcept>

namespace cupola {

namespace {
[[noreturn]] void bad(std::string_view name, std::string_view value, const char* allowed) {
    throw std::invalid_argument("MPCDI reading switch " + std::string(name) + ": '" + std::string(value) +
                                "' is not one of " + allowed);
}
}  // namespace

PfmRows parse_pfm_rows(std::string_view v) {
    if (v == "bottom-first") return PfmRows::bottom_first;
    if (v == "top-first") return PfmRows::top_first;
    bad("pfm_rows", v, "bottom-first, top-first");
}

VOrigin parse_v_origin(std::string_view v) {
    if (v == "bottom") return VOrigin::bottom;
    if (v == "top") return VOrigin::top;
    bad("v_origin", v, "bottom, top");
}

WarpCoordinates parse_warp_coordinates(std::string_view v) {
    if (v == "region") return WarpCoordinates::region;
    if (v == "buffer") return WarpCoordinates::buffer;
    bad("coordinates", v, "region, buffer");
}

WarpDirection parse_warp_direction(std::string_view v) {
    if (v == "forward") return WarpDirection::forward;
    if (v == "inverse") return WarpDirection::inverse;
    bad("warp_direction", v, "forward, inverse");
}

std::string to_string(PfmRows v) { return v == PfmRows::bottom_first ? "bottom-first" : "top-first"; }
std::string to_string(VOrigin v) { return v == VOrigin::bottom ? "bottom" : "top"; }
std::string to_string(WarpCoordinates v) { return v == WarpCoordinates::region ? "region" : "buffer"; }
std::string to_string(WarpDirection v) { return v == WarpDirection::forward ? "forward" : "inverse"; }

void MpcdiReading::set(std::string_view name, std::string_view value) {
    if (name == "pfm_rows")
        pfm_rows = parse_pfm_rows(value);
    else if (name == "v_origin")
        v_origin = parse_v_origin(value);
    else if (name == "coordinates")
        coordinates = parse_warp_coordinates(value);
    else if (name == "warp_direction")
        warp_direction = parse_warp_direction(value);
    else
        throw std::invalid_argument("unknown MPCDI reading switch '" + std::string(name) +
                                    "' (pfm_rows, v_origin, coordinates, warp_direction)");
}

}  // namespace cupola

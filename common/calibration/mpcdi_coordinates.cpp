#include "calibration/mpcdi_coordinates.hpp"

namespace cupola {

namespace {
// Does the file's frame differ from the content's by the region's placement, and which way?
enum class Placement { none, region_to_buffer, buffer_to_region };

Placement placement(const WarpFileFrame& f) {
    if (!f.profile_3d && f.coordinates == WarpCoordinates::region) return Placement::region_to_buffer;
    if (f.profile_3d && f.coordinates == WarpCoordinates::buffer) return Placement::buffer_to_region;
    return Placement::none;
}

glm::dvec2 to_buffer(const WarpFileFrame& f, glm::dvec2 p) { return {f.x + f.x_size * p.x, f.y + f.y_size * p.y}; }
glm::dvec2 to_region(const WarpFileFrame& f, glm::dvec2 p) { return {(p.x - f.x) / f.x_size, (p.y - f.y) / f.y_size}; }
}  // namespace

glm::dvec2 file_to_content(const WarpFileFrame& f, glm::dvec2 p) {
    if (f.v_origin == VOrigin::top) p.y = 1.0 - p.y;
    switch (placement(f)) {
        case Placement::region_to_buffer:
            return to_buffer(f, p);
        case Placement::buffer_to_region:
            return to_region(f, p);
        case Placement::none:
            break;
    }
    return p;
}

glm::dvec2 content_to_file(const WarpFileFrame& f, glm::dvec2 p) {
    switch (placement(f)) {
        case Placement::region_to_buffer:
            p = to_region(f, p);
            break;
        case Placement::buffer_to_region:
            p = to_buffer(f, p);
            break;
        case Placement::none:
            break;
    }
    if (f.v_origin == VOrigin::top) p.y = 1.0 - p.y;
    return p;
}

}  // namespace cupola

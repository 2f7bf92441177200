#pragma once
// Overlay lines on the sky as short arcs of circles on the unit sphere, in an overlay's own frame
// (its z axis the pole: the zenith, the celestial or the ecliptic north pole). The line pass draws
// each arc as a band of a given angular width around its circle: a pixel's coverage comes from its
// own direction's angle to the circle, so a line is equally wide in dome degrees on every channel
// and continues across the edge between two channels (shaders/overlay_lines.*).
#include <glm/glm.hpp>

#include <vector>

namespace cupola {

// The arc from a to b (unit vectors, at most a few degrees apart) of the circle of points p with
// asin(p . pole) = lat_rad: a great circle when lat_rad = 0, else a parallel about `pole`.
struct SkyArc {
    glm::dvec3 a{1.0, 0.0, 0.0}, b{1.0, 0.0, 0.0};
    glm::dvec3 pole{0.0, 0.0, 1.0};
    double lat_rad = 0.0;
};

// The great-circle arc from a to b cut into pieces of at most max_step_rad (a and b unit, not
// antipodal; nothing when they are equal).
void add_great_circle(std::vector<SkyArc>& out, const glm::dvec3& a, const glm::dvec3& b, double max_step_rad);
// The parallel of latitude lat_rad about the frame's z axis, whole, in pieces of at most max_step_rad.
void add_parallel(std::vector<SkyArc>& out, double lat_rad, double max_step_rad);
// The meridian at longitude lon_rad (from the x axis toward y) between latitudes -lat_limit_rad
// and +lat_limit_rad.
void add_meridian(std::vector<SkyArc>& out, double lon_rad, double lat_limit_rad, double max_step_rad);
// A coordinate grid: parallels every parallel_step_deg (not the pole's own latitude, nor 0 unless
// with_equator) and meridians every meridian_step_deg up to the last parallel.
std::vector<SkyArc> coordinate_grid(double parallel_step_deg, double meridian_step_deg, bool with_equator,
                                    double max_step_rad);
// Unit vector of a longitude and latitude in the frame (radians).
glm::dvec3 frame_dir(double lon_rad, double lat_rad);

}  // namespace cupola

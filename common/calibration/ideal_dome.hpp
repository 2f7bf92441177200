#pragma once
// An ideal dome and the projectors that light it: the analytic model the calibration generator
// (tools/mpcdi_gen) writes MPCDI files from and the checks (tests/test_ideal_dome.cpp,
// common/calibration/projector_stitch) compare against.
//
// The dome is a sphere of radius radius_m centred on the audience's eye (the dome frame's origin,
// common/projection/dome_frame.hpp: +Y apex, -Z front, +X right); its screen is the part above
// the springline (the plane y = 0), cut at fov_deg / 2 from the apex. A projector stands at a
// point inside the sphere, its optical frame oriented like a channel (EulerDeg: -Z forward, +Y up),
// and throws one ray per raster point. Raster pixels are (x right, y down), (0,0) the top-left
// corner of the top-left pixel, as in common/calibration/projector_warp.hpp.
//
// Lenses:
//  - fisheye: equidistant (f-theta) projection, Kannala & Brandt (2006) §2 "r = f theta": the angle
//    from the optical axis grows linearly with the distance from the raster centre; a full image
//    circle of fov_deg inscribed in the raster (its diameter is the raster's shorter side), as
//    fisheye projector lenses give it; the raster outside the circle stays dark.
//  - normal: a pinhole (rectilinear) lens, fov_deg across the raster width, with a vertical lens
//    shift: the optical axis meets the raster at y = height * (0.5 + shift_y), so shift_y > 0
//    throws the image upwards (as a projector's lens shift does).
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "projection/dome_frame.hpp"

namespace cupola {

enum class LensKind { Fisheye, Normal };

struct ProjectorLens {
    LensKind kind = LensKind::Fisheye;
    double fov_deg = 180.0;  // fisheye: across the image circle; normal: across the raster width
    double shift_y = 0.0;    // normal lens only: lens shift as a fraction of the raster height
};

struct IdealDome {
    double radius_m = 10.0;
    double fov_deg = 180.0;  // 180: the screen ends at the springline
};

struct ProjectorPlacement {
    std::string id;
    double azimuth_deg = 0.0;        // where on the springline: 0 front, 90 right
    double distance_fraction = 0.9;  // distance from the dome centre, in dome radii (< 1)
    EulerDeg aim;                    // the projector's optical frame in the dome frame
    ProjectorLens lens;
    int raster_width = 640;
    int raster_height = 400;
};

// Position (dome frame, metres) of a point on the springline at an azimuth and distance.
glm::dvec3 springline_position_m(const IdealDome& dome, double azimuth_deg, double distance_fraction);

class IdealProjector {
public:
    IdealProjector(const IdealDome& dome, const ProjectorPlacement& placement);

    // Dome-frame unit ray through a continuous raster position, extended beyond the lit image
    // (a fisheye up to 180 degrees from its axis); nothing where the lens model has no ray.
    std::optional<glm::dvec3> pixel_ray(const glm::dvec2& pixel) const;

    // Whether the lens sends light through this raster position (inside the raster and, for a
    // fisheye, inside the image circle), and the distance in pixels to the lit region's edge.
    bool lit(const glm::dvec2& pixel) const { return lit_edge_distance_px(pixel) >= 0.0; }
    double lit_edge_distance_px(const glm::dvec2& pixel) const;

    // Unit direction, from the dome centre, of the point of the dome sphere this raster position
    // lights (the sphere continues below the springline); nothing where pixel_ray has no ray.
    std::optional<glm::dvec3> pixel_dome_direction(const glm::dvec2& pixel) const;

    // Inverse: the continuous raster position that lights the sphere point in this dome-frame
    // direction, or nothing when the point is behind the lens. May lie outside the raster.
    std::optional<glm::dvec2> dome_direction_to_pixel(const glm::dvec3& dome_dir) const;

    // Angle (radians, seen from the dome centre) one projector pixel spans at this raster
    // position: the mean of the angles between the directions one pixel apart in x and in y.
    double pixel_angle_rad(const glm::dvec2& pixel) const;

    // Whether a dome direction is on the screen (above the cut at fov / 2 from the apex).
    bool on_screen(const glm::dvec3& dome_dir) const;

    // A raster position lit, whose sphere point is on the screen.
    bool lights_screen(const glm::dvec2& pixel) const;

    const ProjectorPlacement& placement() const { return placement_; }
    const IdealDome& dome() const { return dome_; }
    const glm::dvec3& position_m() const { return position_m_; }
    int width() const { return placement_.raster_width; }
    int height() const { return placement_.raster_height; }

private:
    std::optional<glm::dvec3> lens_ray(const glm::dvec2& pixel) const;  // projector frame
    std::optional<glm::dvec2> lens_pixel(const glm::dvec3& ray) const;  // projector frame

    IdealDome dome_;
    ProjectorPlacement placement_;
    glm::dvec3 position_m_;
    glm::dmat3 rotation_;  // projector frame -> dome frame
    glm::dvec2 centre_px_;
    double focal_px_;
    double min_cos_apex_;  // cos of the angle from the apex where the screen ends
};

// N equal projectors around the springline, each standing across the dome from where it aims:
// projector k ("proj<k>") aims at yaw 360 k / N (0 front, 90 right) and pitch_deg, from the
// springline point at azimuth yaw + 180 and distance_fraction radii from the centre.
// The defaults are the demo's dome (configs/dome-4proj.json): four 85-degree fisheyes 0.6 radii
// from the centre, pitched up 30 degrees, lighting the whole dome with two to four of them at the apex.
struct ProjectorRing {
    int count = 4;
    ProjectorLens lens{LensKind::Fisheye, 85.0, 0.0};
    double distance_fraction = 0.6;
    double pitch_deg = 30.0;
    int raster_width = 640;
    int raster_height = 400;
};
std::vector<ProjectorPlacement> projector_ring(const ProjectorRing& ring);

// Builds one IdealProjector per placement; throws std::invalid_argument naming the projector
// when a placement is outside the dome or its raster or lens is impossible.
std::vector<IdealProjector> make_projectors(const IdealDome& dome, const std::vector<ProjectorPlacement>& placements);

}  // namespace cupola

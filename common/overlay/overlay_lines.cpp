#include "overlay/overlay_lines.hpp"

#include <glm/gtc/constants.hpp>

#include <cmath>

namespace cupola {

namespace {

// The polyline without the points that lie within kSimplify_rad of the great circle through their
// neighbours kept (the boundaries run along parallels in many short steps).
constexpr double kSimplify_rad = 1.7e-4;  // 0.01 degrees

std::vector<glm::dvec3> simplified(const std::vector<glm::dvec3>& line) {
    if (line.size() < 3) return line;
    std::vector<glm::dvec3> out = {line.front()};
    for (size_t i = 1; i + 1 < line.size(); ++i) {
        const glm::dvec3 n = glm::cross(out.back(), line[i + 1]);
        const double len = glm::length(n);
        // Keep the point when it bends the line, or when the run would grow past a step.
        const bool bends = !(len > 1e-12) || std::abs(glm::dot(line[i], n / len)) > kSimplify_rad;
        if (bends || glm::dot(out.back(), line[i + 1]) < std::cos(kOverlayArcStep_rad)) out.push_back(line[i]);
    }
    out.push_back(line.back());
    return out;
}

void add_polylines(std::vector<SkyArc>& out, const std::vector<std::vector<glm::dvec3>>& raw, bool closed) {
    for (const auto& r : raw) {
        const std::vector<glm::dvec3> line = simplified(r);
        for (size_t i = 1; i < line.size(); ++i) add_great_circle(out, line[i - 1], line[i], kOverlayArcStep_rad);
        if (closed && line.size() > 2) add_great_circle(out, line.back(), line.front(), kOverlayArcStep_rad);
    }
}

// Above the horizon only: parallels 10 .. 80 degrees up, meridians every 30 degrees from it to 80.
std::vector<SkyArc> altaz_grid() {
    std::vector<SkyArc> out;
    for (int alt = 10; alt <= 80; alt += 10)
        add_parallel(out, glm::radians(static_cast<double>(alt)), kOverlayArcStep_rad);
    for (int az = 0; az < 360; az += 30)
        for (int k = 0; k < 80; k += 2)  // the meridian from the horizon up, two degrees at a time
            out.push_back({frame_dir(glm::radians(static_cast<double>(az)), glm::radians(static_cast<double>(k))),
                           frame_dir(glm::radians(static_cast<double>(az)), glm::radians(k + 2.0)),
                           glm::dvec3(-std::sin(glm::radians(static_cast<double>(az))),
                                      std::cos(glm::radians(static_cast<double>(az))), 0.0),
                           0.0});
    return out;
}

}  // namespace

std::array<std::vector<SkyArc>, kOverlayCount> overlay_lines(const std::vector<ConstellationFigure>& figures) {
    std::array<std::vector<SkyArc>, kOverlayCount> out;
    auto& lines = out[static_cast<size_t>(OverlayKind::Constellations)];
    auto& bounds = out[static_cast<size_t>(OverlayKind::Boundaries)];
    for (const auto& f : figures) {
        add_polylines(lines, f.lines, false);
        add_polylines(bounds, f.boundaries, true);
    }
    out[static_cast<size_t>(OverlayKind::GridAltAz)] = altaz_grid();
    out[static_cast<size_t>(OverlayKind::GridEquatorial)] = coordinate_grid(10.0, 15.0, true, kOverlayArcStep_rad);
    out[static_cast<size_t>(OverlayKind::GridEcliptic)] = coordinate_grid(10.0, 30.0, true, kOverlayArcStep_rad);
    add_parallel(out[static_cast<size_t>(OverlayKind::Horizon)], 0.0, kOverlayArcStep_rad);
    // The meridian: the great circle through north, the zenith and south (azimuths 0 and 180).
    auto& meridian = out[static_cast<size_t>(OverlayKind::Meridian)];
    add_meridian(meridian, 0.0, glm::half_pi<double>(), kOverlayArcStep_rad);
    add_meridian(meridian, glm::pi<double>(), glm::half_pi<double>(), kOverlayArcStep_rad);
    return out;
}

}  // namespace cupola

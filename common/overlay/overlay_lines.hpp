#pragma once
// The lines of every line overlay, in the overlay's own frame (overlay_frames.hpp), cut into arcs
// of at most 2 degrees: the constellation figures and boundaries, the grids (10 degrees of latitude;
// 30 of longitude for the alt-az and ecliptic grids, one hour for the equatorial), the horizon and
// the meridian. Text overlays have none.
#include <array>
#include <vector>

#include "overlay/constellation_figures.hpp"
#include "overlay/overlay_kind.hpp"
#include "overlay/sky_arcs.hpp"

namespace cupola {

inline constexpr double kOverlayArcStep_rad = 0.0349066;  // 2 degrees: the chord sags 0.009 degrees

std::array<std::vector<SkyArc>, kOverlayCount> overlay_lines(const std::vector<ConstellationFigure>& figures);

}  // namespace cupola

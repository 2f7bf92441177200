#pragma once
// The presenter's overlays: what each is called in the scene file, show events and the control
// channel ("show grid equatorial", "hide constellations"). Every overlay's opacity travels in the
// snapshot (RenderSettings::overlay_alpha), one value for the whole cluster.
#include <array>
#include <cstddef>
#include <string>

namespace cupola {

enum class OverlayKind : int {
    Constellations = 0,  // stick figures (d3-celestial's lines, data/sky/constellations.json)
    ConstellationNames,  // their names at the figures' label points
    Boundaries,          // the IAU boundaries
    GridAltAz,           // altitude and azimuth over the observer's ground
    GridEquatorial,      // declination and right ascension (J2000)
    GridEcliptic,        // ecliptic latitude and longitude (J2000, the mean obliquity)
    Horizon,             // altitude 0
    Meridian,            // the great circle through the zenith and the celestial poles
    Cardinals,           // N, E, S, W on the horizon
    Labels,              // the bodies' and the brightest named stars' names
};
inline constexpr size_t kOverlayCount = 10;

// The names, in OverlayKind's order, with '_' where the control channel takes a space:
// constellations, constellation_names, boundaries, grid_altaz, grid_equatorial, grid_ecliptic,
// horizon, meridian, cardinals, labels.
const std::array<std::string, kOverlayCount>& overlay_names();
const std::string& overlay_name(OverlayKind k);
// The kind of a name ("grid equatorial" and "grid_equatorial" alike); throws
// std::invalid_argument listing the names when there is none.
OverlayKind overlay_from_name(const std::string& name);

}  // namespace cupola

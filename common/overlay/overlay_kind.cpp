#include "overlay/overlay_kind.hpp"

#include <algorithm>
#include <stdexcept>

namespace cupola {

const std::array<std::string, kOverlayCount>& overlay_names() {
    static const std::array<std::string, kOverlayCount> names = {"constellations",  "constellation_names",
                                                                 "boundaries",      "grid_altaz",
                                                                 "grid_equatorial", "grid_ecliptic",
                                                                 "horizon",         "meridian",
                                                                 "cardinals",       "labels"};
    return names;
}

const std::string& overlay_name(OverlayKind k) { return overlay_names().at(static_cast<size_t>(k)); }

OverlayKind overlay_from_name(const std::string& name) {
    std::string n = name;
    std::replace(n.begin(), n.end(), ' ', '_');
    const auto& names = overlay_names();
    const auto it = std::find(names.begin(), names.end(), n);
    if (it != names.end()) return static_cast<OverlayKind>(it - names.begin());
    std::string list;
    for (const auto& x : names) list += (list.empty() ? "" : ", ") + x;
    throw std::invalid_argument("\"" + name + "\" is not an overlay (" + list + ")");
}

}  // namespace cupola

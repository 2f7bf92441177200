#include "overlay/overlay_labels.hpp"

#include <cctype>

#include "overlay/sky_arcs.hpp"

namespace cupola {

namespace {

constexpr double kNamedStarLimit = 1.6;  // V: the brightest stars get their names
constexpr double kCardinalAltitude_deg = 2.0;

std::string capitalised(std::string s) {
    if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
    return s;
}

// A proper name, not a Bayer designation such as "alp2Cen".
bool proper_name(const std::string& name) {
    return name.size() > 2 && std::isupper(static_cast<unsigned char>(name[0])) &&
           std::islower(static_cast<unsigned char>(name[1]));
}

}  // namespace

std::vector<OverlayLabel> overlay_labels(const std::vector<ConstellationFigure>& figures, const SceneConfig& scene,
                                         const std::vector<Star>& stars) {
    std::vector<OverlayLabel> out;
    for (const auto& f : figures)
        for (const auto& l : f.labels) out.push_back({OverlayKind::ConstellationNames, l.text, l.dir});
    // Azimuth from north toward east; the horizon frame's y axis is west.
    const char* cardinal[] = {"N", "E", "S", "W"};
    for (int k = 0; k < 4; ++k)
        out.push_back({OverlayKind::Cardinals, cardinal[k],
                       frame_dir(-glm::radians(90.0 * k), glm::radians(kCardinalAltitude_deg))});
    for (const Star& s : stars)
        if (s.v_mag <= kNamedStarLimit && proper_name(s.name))
            out.push_back({OverlayKind::Labels, s.name, s.direction(), LabelPlacement::Beside});
    for (const BodyConfig& b : scene.bodies)
        out.push_back(
            {OverlayKind::Labels, capitalised(b.name), glm::dvec3(0.0, 0.0, 1.0), LabelPlacement::Beside, b.id});
    return out;
}

}  // namespace cupola

#include "calibration/dome_blend.hpp"

#include <algorithm>

namespace cupola {

namespace {
double smoothstep(double edge0, double edge1, double x) {
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}
}  // namespace

double blend_weight(const IdealProjector& projector, const glm::dvec3& dome_dir, const BlendRamp& ramp) {
    if (!projector.on_screen(dome_dir)) return 0.0;
    auto px = projector.dome_direction_to_pixel(dome_dir);
    if (!px) return 0.0;
    const double edge = projector.lit_edge_distance_px(*px);
    if (edge < 0.0) return 0.0;
    return smoothstep(0.0, ramp.width_px, edge);
}

double blend_alpha(const std::vector<IdealProjector>& projectors, size_t index, const glm::dvec2& pixel,
                   const BlendRamp& ramp) {
    const IdealProjector& self = projectors.at(index);
    if (!self.lights_screen(pixel)) return 0.0;
    const auto dir = self.pixel_dome_direction(pixel);
    const double own = smoothstep(0.0, ramp.width_px, self.lit_edge_distance_px(pixel));
    double sum = own;
    for (size_t j = 0; j < projectors.size(); ++j)
        if (j != index) sum += blend_weight(projectors[j], *dir, ramp);
    return sum > 1e-12 ? own / sum : 1.0;
}

BlendMap dome_alpha_map(const std::vector<IdealProjector>& projectors, size_t index, int width, int height,
                        const BlendRamp& ramp) {
    const IdealProjector& self = projectors.at(index);
    BlendMap map;
    map.width = width;
    map.height = height;
    map.value.resize(static_cast<size_t>(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::dvec2 p((x + 0.5) * self.width() / width, (y + 0.5) * self.height() / height);
            map.value[static_cast<size_t>(y) * width + x] = static_cast<float>(blend_alpha(projectors, index, p, ramp));
        }
    return map;
}

}  // namespace cupola

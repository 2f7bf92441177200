#include "passes/ring_profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cupola {

namespace {

// Each column's mean luminance over the rows (linear).
std::vector<double> column_means(const BodyImage& map) {
    std::vector<double> mean(static_cast<size_t>(map.width), 0.0);
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            const float* p = &map.rgb[(static_cast<size_t>(y) * map.width + x) * 3];
            mean[x] += (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / map.height;
        }
    return mean;
}

}  // namespace

RingProfile make_ring_profile(const RingConfig& rings, const BodyImage& map, double planet_radius_m) {
    if (map.width < 2 || map.height < 1)
        throw std::invalid_argument("ring map \"" + rings.texture + "\": needs at least two columns");
    RingProfile p;
    p.inner_radius = rings.inner_radius_m / planet_radius_m;
    p.outer_radius = rings.outer_radius_m / planet_radius_m;
    p.tau.assign(1, 0.0f);
    p.albedo.assign(1, 0.0f);
    for (const double g : column_means(map)) {
        const double v = std::clamp(g, 0.0, 1.0);
        p.tau.push_back(static_cast<float>(rings.optical_depth * v * v));
        p.albedo.push_back(static_cast<float>(v));
    }
    p.tau.push_back(0.0f);
    p.albedo.push_back(0.0f);
    p.mips = box_filter_mip_chain(static_cast<int>(p.tau.size()), 1, p.texels_rgb());
    return p;
}

glm::dvec2 RingProfile::radius_to_texture() const {
    // Column i (1 .. n, texel i of n + 2) is at s = (i + 0.5) / (n + 2): column 1 at the inner
    // radius, column n at the outer.
    const double n = static_cast<double>(tau.size()) - 2.0, texels = n + 2.0;
    const double per_radius = (n - 1.0) / (outer_radius - inner_radius);
    return {per_radius / texels, (1.5 - inner_radius * per_radius) / texels};
}

double RingProfile::at(const std::vector<float>& texels, double r) const {
    const glm::dvec2 m = radius_to_texture();
    const double s = r * m.x + m.y;
    if (s < 0.0 || s > 1.0) return 0.0;
    const double x = std::clamp(s * static_cast<double>(tau.size()) - 0.5, 0.0, static_cast<double>(tau.size() - 1));
    const size_t i = std::min(static_cast<size_t>(x), tau.size() - 2);
    return texels[i] + (x - static_cast<double>(i)) * (texels[i + 1] - texels[i]);
}

std::vector<float> RingProfile::texels_rgb() const {
    std::vector<float> rgb;
    rgb.reserve(tau.size() * 3);
    for (size_t i = 0; i < tau.size(); ++i) rgb.insert(rgb.end(), {tau[i], albedo[i], 0.0f});
    return rgb;
}

}  // namespace cupola

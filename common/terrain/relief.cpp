#include "terrain/relief.hpp"

#include <algorithm>
#include <cmath>

#include "terrain/cube_sphere.hpp"

namespace cupola::terrain {

Relief::Relief(double radius_m, std::shared_ptr<const ElevationRaster> data, const ProceduralRelief& procedural)
    : radius_m_(radius_m), data_(std::move(data)), procedural_(procedural) {
    const double detail = procedural_.amplitude_bound_m();
    if (data_) {
        detail_below_m_ = 2.0 * data_->sample_spacing_rad() * radius_m_;
        min_m_ = std::min(data_->min_height_m() - detail, -detail);
        max_m_ = std::max(data_->max_height_m() + detail, detail);
    } else {
        min_m_ = -detail;
        max_m_ = detail;
    }
}

double Relief::height_m(const glm::dvec3& dir, double spacing_m) const {
    const glm::dvec3 p = dir * radius_m_;
    if (!data_) return procedural_.height_m(p, spacing_m);
    const glm::dvec2 ll = direction_to_lat_lon_rad(dir);
    const std::optional<double> h = data_->height_m(ll.x, ll.y);
    // Outside the data's extent, or at a no-data sample: the procedural relief whole.
    return h ? *h + procedural_.height_m(p, spacing_m, detail_below_m_) : procedural_.height_m(p, spacing_m);
}

bool Relief::data_covers(const glm::dvec3& dir) const {
    if (!data_) return false;
    const glm::dvec2 ll = direction_to_lat_lon_rad(dir);
    return data_->height_m(ll.x, ll.y).has_value();
}

double Relief::mesh_error_m(double spacing_m) const {
    const double procedural_alone = procedural_.mesh_error_m(spacing_m);
    if (!data_) return procedural_alone;
    const double with_data =
        procedural_.mesh_error_m(spacing_m, detail_below_m_) + data_->max_rise_m_per_rad() / radius_m_ * spacing_m;
    return std::max(with_data, procedural_alone);
}

}  // namespace cupola::terrain

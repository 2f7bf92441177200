#include "calibration/ideal_dome.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cupola {

namespace {
constexpr double kPi = 3.14159265358979323846;

void check_placement(const IdealDome& dome, const ProjectorPlacement& p) {
    const std::string where = "projector '" + p.id + "': ";
    if (!(dome.radius_m > 0.0)) throw std::invalid_argument(where + "dome radius_m must be > 0");
    if (!(dome.fov_deg > 0.0 && dome.fov_deg <= 180.0))
        throw std::invalid_argument(where + "dome fov_deg must be in (0, 180]");
    if (!(p.distance_fraction >= 0.0 && p.distance_fraction < 1.0))
        throw std::invalid_argument(where +
                                    "distance_fraction must be in [0, 1): the projector stands inside the dome");
    if (p.raster_width < 2 || p.raster_height < 2)
        throw std::invalid_argument(where + "raster must be at least 2x2 pixels");
    const double max_fov = p.lens.kind == LensKind::Fisheye ? 360.0 : 179.0;
    if (!(p.lens.fov_deg > 0.0 && p.lens.fov_deg < max_fov))
        throw std::invalid_argument(where + "lens fov_deg out of range");
}
}  // namespace

glm::dvec3 springline_position_m(const IdealDome& dome, double azimuth_deg, double distance_fraction) {
    const double a = glm::radians(azimuth_deg), r = dome.radius_m * distance_fraction;
    return {r * std::sin(a), 0.0, -r * std::cos(a)};
}

IdealProjector::IdealProjector(const IdealDome& dome, const ProjectorPlacement& placement)
    : dome_(dome), placement_(placement) {
    check_placement(dome, placement);
    position_m_ = springline_position_m(dome, placement.azimuth_deg, placement.distance_fraction);
    rotation_ = channel_rotation(placement.aim);
    const double w = placement.raster_width, h = placement.raster_height;
    const double half_fov_rad = glm::radians(placement.lens.fov_deg) * 0.5;
    if (placement.lens.kind == LensKind::Fisheye) {
        centre_px_ = {0.5 * w, 0.5 * h};
        focal_px_ = 0.5 * std::min(w, h) / half_fov_rad;  // r = f * theta reaches the circle at fov / 2
    } else {
        centre_px_ = {0.5 * w, h * (0.5 + placement.lens.shift_y)};
        focal_px_ = 0.5 * w / std::tan(half_fov_rad);
    }
    min_cos_apex_ = std::cos(glm::radians(dome.fov_deg) * 0.5);
}

std::optional<glm::dvec3> IdealProjector::lens_ray(const glm::dvec2& pixel) const {
    const glm::dvec2 d = pixel - centre_px_;
    if (placement_.lens.kind == LensKind::Normal)
        return glm::normalize(glm::dvec3(d.x / focal_px_, -d.y / focal_px_, -1.0));
    const double r = glm::length(d), theta = r / focal_px_;
    if (theta >= kPi) return std::nullopt;
    if (r < 1e-12) return glm::dvec3(0.0, 0.0, -1.0);
    const double s = std::sin(theta) / r;
    return glm::dvec3(d.x * s, -d.y * s, -std::cos(theta));
}

std::optional<glm::dvec2> IdealProjector::lens_pixel(const glm::dvec3& ray) const {
    const glm::dvec3 v = glm::normalize(ray);
    if (placement_.lens.kind == LensKind::Normal) {
        if (v.z >= -1e-12) return std::nullopt;
        return centre_px_ + focal_px_ * glm::dvec2(v.x / -v.z, -v.y / -v.z);
    }
    const double theta = std::acos(std::clamp(-v.z, -1.0, 1.0));
    const double s = std::hypot(v.x, v.y);
    if (theta >= kPi - 1e-9) return std::nullopt;
    if (s < 1e-15) return centre_px_;
    return centre_px_ + (focal_px_ * theta / s) * glm::dvec2(v.x, -v.y);
}

std::optional<glm::dvec3> IdealProjector::pixel_ray(const glm::dvec2& pixel) const {
    auto ray = lens_ray(pixel);
    if (!ray) return std::nullopt;
    return rotation_ * *ray;
}

double IdealProjector::lit_edge_distance_px(const glm::dvec2& p) const {
    const double w = placement_.raster_width, h = placement_.raster_height;
    double d = std::min(std::min(p.x, w - p.x), std::min(p.y, h - p.y));
    if (placement_.lens.kind == LensKind::Fisheye) d = std::min(d, 0.5 * std::min(w, h) - glm::length(p - centre_px_));
    return d;
}

std::optional<glm::dvec3> IdealProjector::pixel_dome_direction(const glm::dvec2& pixel) const {
    auto ray = pixel_ray(pixel);
    if (!ray) return std::nullopt;
    // |C + t d| = R with |C| < R: one positive root, t = -b + sqrt(b^2 - c).
    const double b = glm::dot(position_m_, *ray);
    const double c = glm::dot(position_m_, position_m_) - dome_.radius_m * dome_.radius_m;
    const double t = -b + std::sqrt(b * b - c);
    return glm::normalize(position_m_ + t * *ray);
}

std::optional<glm::dvec2> IdealProjector::dome_direction_to_pixel(const glm::dvec3& dome_dir) const {
    const glm::dvec3 towards = dome_.radius_m * glm::normalize(dome_dir) - position_m_;
    return lens_pixel(glm::transpose(rotation_) * towards);
}

double IdealProjector::pixel_angle_rad(const glm::dvec2& pixel) const {
    auto angle = [](const std::optional<glm::dvec3>& a, const std::optional<glm::dvec3>& b) {
        return std::acos(std::clamp(glm::dot(*a, *b), -1.0, 1.0));
    };
    const auto left = pixel_dome_direction(pixel - glm::dvec2(0.5, 0.0));
    const auto right = pixel_dome_direction(pixel + glm::dvec2(0.5, 0.0));
    const auto up = pixel_dome_direction(pixel - glm::dvec2(0.0, 0.5));
    const auto down = pixel_dome_direction(pixel + glm::dvec2(0.0, 0.5));
    if (!left || !right || !up || !down) return 0.0;
    return 0.5 * (angle(left, right) + angle(up, down));
}

bool IdealProjector::on_screen(const glm::dvec3& dome_dir) const {
    return dome_dir.y >= min_cos_apex_ * glm::length(dome_dir) - 1e-12;
}

bool IdealProjector::lights_screen(const glm::dvec2& pixel) const {
    if (!lit(pixel)) return false;
    auto dir = pixel_dome_direction(pixel);
    return dir && on_screen(*dir);
}

std::vector<ProjectorPlacement> projector_ring(const ProjectorRing& ring) {
    std::vector<ProjectorPlacement> out;
    for (int k = 0; k < ring.count; ++k) {
        ProjectorPlacement p;
        p.id = "proj" + std::to_string(k);
        p.aim.yaw_deg = 360.0 * k / ring.count;
        p.aim.pitch_deg = ring.pitch_deg;
        p.azimuth_deg = std::fmod(p.aim.yaw_deg + 180.0, 360.0);
        p.distance_fraction = ring.distance_fraction;
        p.lens = ring.lens;
        p.raster_width = ring.raster_width;
        p.raster_height = ring.raster_height;
        out.push_back(p);
    }
    return out;
}

std::vector<IdealProjector> make_projectors(const IdealDome& dome, const std::vector<ProjectorPlacement>& placements) {
    std::vector<IdealProjector> out;
    out.reserve(placements.size());
    for (const auto& p : placements) out.emplace_back(dome, p);
    return out;
}

}  // namespace cupola

#include "calibration/ideal_dome_checks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "calibration/projector_stitch.hpp"
#include "projection/fisheye.hpp"

namespace cupola {

namespace {
double quantile(std::vector<double>& v, double q) {
    if (v.empty()) return 0.0;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

// Angle, in projector pixels, between the warp's and the model's direction at one pixel centre;
// negative when the warp shows nothing there.
double pixel_error_px(const IdealProjector& p, const ProjectorWarp& w, const ChannelFrustum& channel,
                      const glm::dvec2& px) {
    const auto uv = sample_warp_grid(w, px);
    if (!uv) return -1.0;
    const glm::dvec3 shown =
        channel.pixel_to_dome_direction({uv->x * channel.width(), (1.0 - uv->y) * channel.height()});
    const glm::dvec3 truth = *p.pixel_dome_direction(px);
    const double angle = std::acos(std::clamp(glm::dot(shown, truth), -1.0, 1.0));
    return angle / p.pixel_angle_rad(px);
}

void check_sizes(const std::vector<IdealProjector>& projectors, const std::vector<ProjectorWarp>& warps) {
    if (projectors.size() != warps.size()) throw std::invalid_argument("ideal dome check: one warp per projector");
    for (const auto& w : warps)
        if (!w.frustum) throw std::invalid_argument(w.source + ": no frustum (3d profile) to check the warp against");
}
}  // namespace

WarpGeometryError measure_warp_geometry(const std::vector<IdealProjector>& projectors,
                                        const std::vector<ProjectorWarp>& warps) {
    check_sizes(projectors, warps);
    WarpGeometryError e;
    std::vector<double> errors;
    for (size_t k = 0; k < projectors.size(); ++k) {
        const IdealProjector& p = projectors[k];
        const ChannelFrustum channel(warps[k].frustum->orientation, warps[k].frustum->fov, 1024, 1024);
        for (int y = 0; y < p.height(); ++y)
            for (int x = 0; x < p.width(); ++x) {
                const glm::dvec2 px(x + 0.5, y + 0.5);
                if (!p.lights_screen(px)) continue;
                ++e.pixels;
                const double err = pixel_error_px(p, warps[k], channel, px);
                if (err < 0.0)
                    ++e.not_shown;
                else
                    errors.push_back(err);
            }
    }
    if (!errors.empty()) e.max_px = *std::max_element(errors.begin(), errors.end());
    e.median_px = quantile(errors, 0.5);
    e.p99_px = quantile(errors, 0.99);
    return e;
}

std::vector<Image> white_field_frames(const std::vector<ProjectorWarp>& warps, const ProjectorFrameOptions& options) {
    Image white;
    white.width = white.height = 16;
    white.rgba.assign(16 * 16 * 4, 1.0f);
    std::vector<Image> frames;
    for (const auto& w : warps) frames.push_back(reference_projector_frame(w, white, options));
    return frames;
}

BlendFlatness measure_blend_flatness(const std::vector<IdealProjector>& projectors,
                                     const std::vector<ProjectorWarp>& warps, const ProjectorFrameOptions& options,
                                     int samples, double margin_deg) {
    check_sizes(projectors, warps);
    const auto frames = white_field_frames(warps, options);
    std::vector<double> gammas;
    for (const auto& w : warps) gammas.push_back(w.projector_gamma);
    const FisheyeMapping fisheye(180.0);
    const double min_y = std::sin(glm::radians(margin_deg));
    BlendFlatness b;
    b.min_light = 1e300;
    for (int y = 0; y < samples; ++y)
        for (int x = 0; x < samples; ++x) {
            const auto d = fisheye.uv_to_direction(FisheyeMapping::pixel_to_uv({x + 0.5, y + 0.5}, samples));
            if (!d || d->y < min_y) continue;
            int lit_by = 0;
            for (const auto& p : projectors) {
                const auto px = p.dome_direction_to_pixel(*d);
                lit_by += px && p.lit(*px) ? 1 : 0;
            }
            const double light = dome_light(projectors, frames, gammas, *d).g;
            const double dev = std::abs(light - 1.0);
            ++b.samples;
            b.dark_samples += lit_by == 0 ? 1 : 0;
            b.min_light = std::min(b.min_light, light), b.max_light = std::max(b.max_light, light);
            b.max_deviation = std::max(b.max_deviation, dev);
            if (lit_by >= 2) ++b.overlap_samples, b.max_overlap_deviation = std::max(b.max_overlap_deviation, dev);
        }
    return b;
}

}  // namespace cupola

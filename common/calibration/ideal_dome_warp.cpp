#include "calibration/ideal_dome_warp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cupola {

namespace {
EulerDeg aim_at(const glm::dvec3& dir) {
    EulerDeg e;
    e.yaw_deg = glm::degrees(std::atan2(dir.x, -dir.z));
    e.pitch_deg = glm::degrees(std::asin(std::clamp(dir.y, -1.0, 1.0)));
    return e;
}

glm::dvec3 mean_direction(const std::vector<glm::dvec3>& dirs, const std::string& id) {
    glm::dvec3 sum(0.0);
    for (const auto& d : dirs) sum += d;
    if (dirs.empty() || glm::length(sum) < 1e-9 * static_cast<double>(dirs.size()))
        throw std::invalid_argument("projector '" + id + "': no footprint on the dome to fit a channel frustum to");
    return glm::normalize(sum);
}

// The four tangents (left, right, up, down) that hold every footprint direction in a frustum
// aimed at `aim`; nothing when a direction is within 5 degrees of the frustum's side plane.
std::optional<glm::dvec4> footprint_tangents(const EulerDeg& aim, const std::vector<glm::dvec3>& footprint) {
    const glm::dmat3 to_channel = glm::transpose(channel_rotation(aim));
    glm::dvec4 t(0.0);
    for (const auto& d : footprint) {
        const glm::dvec3 c = to_channel * d;
        if (c.z > -std::cos(glm::radians(85.0))) return std::nullopt;
        const double tx = c.x / -c.z, ty = c.y / -c.z;
        t = glm::max(t, glm::dvec4(-tx, tx, ty, -ty));
    }
    return t;
}
}  // namespace

CalibratedFrustum fit_channel_frustum(const IdealProjector& projector, const std::vector<glm::dvec3>& footprint,
                                      double margin_deg) {
    const std::string& id = projector.placement().id;
    // Yaw at the footprint's mean direction; the pitch that gives the smallest image plane
    // ((tl + tr)(tu + td), what the render's pixels are spread over), searched in 0.25 degree steps.
    const EulerDeg mean_aim = aim_at(mean_direction(footprint, id));
    std::optional<glm::dvec4> best;
    EulerDeg aim = mean_aim;
    for (double dp = -30.0; dp <= 30.0; dp += 0.25) {
        EulerDeg a = mean_aim;
        a.pitch_deg = std::clamp(mean_aim.pitch_deg + dp, -89.0, 89.0);
        const auto t = footprint_tangents(a, footprint);
        if (t && (!best || (t->x + t->y) * (t->z + t->w) < (best->x + best->y) * (best->z + best->w)))
            best = t, aim = a;
    }
    if (!best) throw std::invalid_argument("projector '" + id + "': footprint too wide for one channel frustum");
    auto angle = [&](double t) { return std::min(glm::degrees(std::atan(t)) + margin_deg, 89.0); };
    return {aim, FovDeg{angle(best->x), angle(best->y), angle(best->z), angle(best->w)}};
}

std::vector<bool> needed_grid_points(const IdealProjector& projector, int columns, int rows) {
    std::vector<bool> lights(static_cast<size_t>(columns) * rows), needed(lights.size(), false);
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i)
            lights[j * columns + i] =
                projector.lights_screen(grid_point_pixel(i, j, columns, rows, projector.width(), projector.height()));
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            if (!lights[j * columns + i]) continue;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int ii = i + di, jj = j + dj;
                    if (ii >= 0 && ii < columns && jj >= 0 && jj < rows) needed[jj * columns + ii] = true;
                }
        }
    return needed;
}

std::vector<glm::dvec3> needed_grid_directions(const IdealProjector& projector, int columns, int rows) {
    const auto needed = needed_grid_points(projector, columns, rows);
    std::vector<glm::dvec3> dirs;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            if (!needed[j * columns + i]) continue;
            auto d = projector.pixel_dome_direction(
                grid_point_pixel(i, j, columns, rows, projector.width(), projector.height()));
            if (d) dirs.push_back(*d);
        }
    return dirs;
}

WarpGrid ideal_warp_grid(const IdealProjector& projector, const ChannelFrustum& channel, int columns, int rows) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const auto needed = needed_grid_points(projector, columns, rows);
    WarpGrid grid;
    grid.columns = columns;
    grid.rows = rows;
    grid.uv.assign(needed.size(), glm::dvec2(nan));
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            if (!needed[j * columns + i]) continue;
            auto d = projector.pixel_dome_direction(
                grid_point_pixel(i, j, columns, rows, projector.width(), projector.height()));
            auto px = d ? channel.dome_direction_to_pixel(*d) : std::nullopt;
            if (!px) continue;
            grid.uv[j * columns + i] = {px->x / channel.width(), 1.0 - px->y / channel.height()};
        }
    return grid;
}

std::vector<ProjectorWarp> ideal_projector_warps(const IdealCalibrationSpec& spec) {
    const auto projectors = make_projectors(spec.dome, spec.projectors);
    std::vector<ProjectorWarp> warps;
    for (size_t k = 0; k < projectors.size(); ++k) {
        const IdealProjector& p = projectors[k];
        ProjectorWarp w;
        w.region_id = p.placement().id;
        w.source = spec.source + " region " + w.region_id;
        w.raster_width = p.width();
        w.raster_height = p.height();
        const auto footprint = needed_grid_directions(p, spec.grid_columns, spec.grid_rows);
        const CalibratedFrustum frustum = fit_channel_frustum(p, footprint, spec.frustum_margin_deg);
        w.frustum = frustum;
        // The warp's (u, v) are fractions of the render, so any render size gives the same grid.
        const ChannelFrustum channel(frustum.orientation, frustum.fov, p.width(), p.height());
        w.grid = ideal_warp_grid(p, channel, spec.grid_columns, spec.grid_rows);
        const int aw = spec.alpha_width > 0 ? spec.alpha_width : std::max(2, p.width() / 2);
        const int ah = spec.alpha_height > 0 ? spec.alpha_height : std::max(2, p.height() / 2);
        w.alpha = dome_alpha_map(projectors, k, aw, ah, spec.ramp);
        w.projector_gamma = spec.projector_gamma;
        warps.push_back(std::move(w));
    }
    return warps;
}

}  // namespace cupola

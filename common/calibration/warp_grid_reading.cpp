#include "calibration/warp_grid_reading.hpp"

#include <cmath>
#include <limits>

#include "calibration/calibration_error.hpp"
#include "calibration/mesh_resampling.hpp"

namespace cupola {

namespace {

const double nan_value = std::numeric_limits<double>::quiet_NaN();

bool shown(const glm::dvec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

void check_size(const PfmImage& pfm, const WarpGridReading& r, const std::string& name) {
    if (pfm.channels != 3)
        throw CalibrationError(
            name, "PFM channels",
            "a 2d warp needs 3 channels (PF: u, v, error), the file has " + std::to_string(pfm.channels) + " (Pf)");
    if (pfm.width < 2 || pfm.height < 2)
        throw CalibrationError(name, "PFM size", "the warp grid needs at least 2x2 points");
    if (pfm.width > r.raster_width || pfm.height > r.raster_height)
        throw CalibrationError(name, "PFM size",
                               std::to_string(pfm.width) + "x" + std::to_string(pfm.height) +
                                   " points, more than the region's xResolution x yResolution " +
                                   std::to_string(r.raster_width) + "x" + std::to_string(r.raster_height));
}

// The file's own numbers per grid point, NaN pairs where either is NaN; infinities are errors.
std::vector<glm::dvec2> file_values(const PfmImage& pfm, const std::string& name) {
    std::vector<glm::dvec2> v(static_cast<size_t>(pfm.width) * pfm.height);
    for (int j = 0; j < pfm.height; ++j)
        for (int i = 0; i < pfm.width; ++i) {
            const double u = pfm.at(i, j, 0), w = pfm.at(i, j, 1);
            if (std::isinf(u) || std::isinf(w))
                throw CalibrationError(name, "PFM point (" + std::to_string(i) + ", " + std::to_string(j) + ")",
                                       "infinite value");
            v[static_cast<size_t>(j) * pfm.width + i] =
                std::isnan(u) || std::isnan(w) ? glm::dvec2(nan_value) : glm::dvec2(u, w);
        }
    return v;
}

// Inverse map: nodes at the content points (in the file's frame), positions in projector space
// (x right, y up, normalized); resampled at the projector grid's fill-layout points.
std::vector<glm::dvec2> invert(const std::vector<glm::dvec2>& values, int columns, int rows, VOrigin v_origin) {
    NodeMesh mesh{columns, rows, {}, {}};
    mesh.position.resize(values.size());
    mesh.value.resize(values.size());
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const size_t k = static_cast<size_t>(j) * columns + i;
            const double v_up = 1.0 - (j + 0.5) / rows;
            mesh.value[k] = glm::dvec3((i + 0.5) / columns, v_origin == VOrigin::top ? 1.0 - v_up : v_up, 0.0);
            glm::dvec2 p = values[k];
            if (v_origin == VOrigin::top) p.y = 1.0 - p.y;
            mesh.position[k] = p;
        }
    const auto out = resample_mesh(mesh, columns, rows, glm::dvec2(0.5 / columns, 1.0 - 0.5 / rows),
                                   glm::dvec2(1.0 / columns, -1.0 / rows));
    std::vector<glm::dvec2> forward(out.size());
    for (size_t k = 0; k < out.size(); ++k) forward[k] = glm::dvec2(out[k]);
    return forward;
}

// Orientation counts of the grid's cells (cross product of their edges), for the fold check.
void count_orientations(const WarpGrid& g, size_t& positive, size_t& negative) {
    positive = negative = 0;
    for (int j = 0; j + 1 < g.rows; ++j)
        for (int i = 0; i + 1 < g.columns; ++i) {
            const glm::dvec2 a = g.uv[j * g.columns + i], b = g.uv[j * g.columns + i + 1],
                             c = g.uv[(j + 1) * g.columns + i];
            if (!shown(a) || !shown(b) || !shown(c)) continue;
            const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            if (cross > 0.0) ++positive;
            if (cross < 0.0) ++negative;
        }
}

}  // namespace

void check_warp_grid(const WarpGrid& g, const std::string& name) {
    size_t count = 0, outside = 0;
    for (const glm::dvec2& p : g.uv) {
        if (!shown(p)) continue;
        ++count;
        if (p.x < -1e-3 || p.x > 1.001 || p.y < -1e-3 || p.y > 1.001) ++outside;
    }
    if (count == 0) throw CalibrationError(name, "warp grid", "every point is NaN: the projector shows nothing");
    if (2 * outside > count)
        throw CalibrationError(name, "warp grid values",
                               std::to_string(outside) + " of " + std::to_string(count) +
                                   " points are outside [0,1]: pixel units, buffer-global values read as "
                                   "region-local, or an inverse map read as forward? (coordinates, warp_direction)");
    size_t positive, negative;
    count_orientations(g, positive, negative);
    const size_t cells = positive + negative;
    if (cells > 0 && 10 * positive > cells && 10 * negative > cells)
        throw CalibrationError(name, "warp grid values",
                               "the map folds over itself (" + std::to_string(positive) + " cells one way, " +
                                   std::to_string(negative) + " the other): wrong warp_direction or a damaged file");
}

WarpGrid warp_grid_from_pfm(const PfmImage& pfm, const WarpGridReading& r, const std::string& name) {
    check_size(pfm, r, name);
    std::vector<glm::dvec2> values = file_values(pfm, name);
    if (r.direction == WarpDirection::inverse) {
        WarpGrid as_read{pfm.width, pfm.height, values, {}};
        check_warp_grid(as_read, name + " (inverse map)");
        values = invert(values, pfm.width, pfm.height, r.frame.v_origin);
    }
    WarpGrid g{pfm.width, pfm.height, std::vector<glm::dvec2>(values.size()), {}};
    for (size_t k = 0; k < values.size(); ++k)
        g.uv[k] = shown(values[k]) ? file_to_content(r.frame, values[k]) : glm::dvec2(nan_value);
    check_warp_grid(g, name);
    return g;
}

}  // namespace cupola

#include "calibration/reference_warp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cupola {

namespace {

// Bilinear weights at a continuous sample position s (in units of points, point k at k) over n
// points, clamped to the outer point centres.
void bracket(double s, int n, int& k0, int& k1, double& t) {
    s = std::clamp(s, 0.0, static_cast<double>(n - 1));
    k0 = std::min(static_cast<int>(std::floor(s)), n - 2);
    k1 = k0 + 1;
    t = s - k0;
}

double blend_at(const BlendMap& m, double fx, double fy, double fallback) {
    if (m.empty()) return fallback;
    int x0, x1, y0, y1;
    double tx, ty;
    if (m.width == 1 && m.height == 1) return m.value[0];
    bracket(fx * m.width - 0.5, std::max(m.width, 2), x0, x1, tx);
    bracket(fy * m.height - 0.5, std::max(m.height, 2), y0, y1, ty);
    x0 = std::min(x0, m.width - 1), x1 = std::min(x1, m.width - 1);
    y0 = std::min(y0, m.height - 1), y1 = std::min(y1, m.height - 1);
    auto at = [&](int x, int y) { return static_cast<double>(m.value[static_cast<size_t>(y) * m.width + x]); };
    return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1 - tx) * at(x0, y1) + tx * at(x1, y1));
}

double intensity_at(const ProjectorWarp& w, double x_px, double y_px) {
    const WarpGrid& g = w.grid;
    if (g.intensity.empty()) return 1.0;
    int i0, i1, j0, j1;
    double tx, ty;
    bracket(x_px * g.columns / w.raster_width - 0.5, g.columns, i0, i1, tx);
    bracket(y_px * g.rows / w.raster_height - 0.5, g.rows, j0, j1, ty);
    auto at = [&](int i, int j) { return static_cast<double>(g.intensity[static_cast<size_t>(j) * g.columns + i]); };
    return (1 - ty) * ((1 - tx) * at(i0, j0) + tx * at(i1, j0)) + ty * ((1 - tx) * at(i0, j1) + tx * at(i1, j1));
}

void sample_content(const LinearImage& c, glm::dvec2 uv, float* out) {
    int x0, x1, y0, y1;
    double tx, ty;
    bracket(uv.x * c.width - 0.5, std::max(c.width, 2), x0, x1, tx);
    bracket((1.0 - uv.y) * c.height - 0.5, std::max(c.height, 2), y0, y1, ty);
    x0 = std::min(x0, c.width - 1), x1 = std::min(x1, c.width - 1);
    y0 = std::min(y0, c.height - 1), y1 = std::min(y1, c.height - 1);
    for (int ch = 0; ch < c.channels; ++ch) {
        auto at = [&](int x, int y) {
            return static_cast<double>(c.data[(static_cast<size_t>(y) * c.width + x) * c.channels + ch]);
        };
        out[ch] = static_cast<float>((1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x1, y0)) +
                                     ty * ((1 - tx) * at(x0, y1) + tx * at(x1, y1)));
    }
}

}  // namespace

glm::dvec2 warp_uv_at(const ProjectorWarp& w, double x_px, double y_px) {
    const WarpGrid& g = w.grid;
    int i0, i1, j0, j1;
    double tx, ty;
    bracket(x_px * g.columns / w.raster_width - 0.5, g.columns, i0, i1, tx);
    bracket(y_px * g.rows / w.raster_height - 0.5, g.rows, j0, j1, ty);
    auto at = [&](int i, int j) { return g.uv[static_cast<size_t>(j) * g.columns + i]; };
    const glm::dvec2 a = at(i0, j0), b = at(i1, j0), c = at(i0, j1), d = at(i1, j1);
    if (!std::isfinite(a.x + a.y + b.x + b.y + c.x + c.y + d.x + d.y))
        return glm::dvec2(std::numeric_limits<double>::quiet_NaN());
    return (1 - ty) * ((1 - tx) * a + tx * b) + ty * ((1 - tx) * c + tx * d);
}

LinearImage reference_warp(const ProjectorWarp& w, const LinearImage& content) {
    LinearImage out{w.raster_width, w.raster_height, content.channels,
                    std::vector<float>(static_cast<size_t>(w.raster_width) * w.raster_height * content.channels)};
    std::vector<float> c(content.channels);
    for (int y = 0; y < w.raster_height; ++y)
        for (int x = 0; x < w.raster_width; ++x) {
            const double px = x + 0.5, py = y + 0.5;
            const glm::dvec2 uv = warp_uv_at(w, px, py);
            const bool inside = std::isfinite(uv.x) && uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0;
            std::fill(c.begin(), c.end(), 0.0f);
            if (inside) sample_content(content, uv, c.data());
            const double fx = px / w.raster_width, fy = py / w.raster_height;
            const double alpha = blend_at(w.alpha, fx, fy, 1.0) * intensity_at(w, px, py);
            const double beta = blend_at(w.beta, fx, fy, 0.0);
            float* o = &out.data[(static_cast<size_t>(y) * w.raster_width + x) * content.channels];
            for (int ch = 0; ch < content.channels; ++ch)
                o[ch] = static_cast<float>(c[ch] * alpha * (1.0 - beta) + beta);
        }
    return out;
}

}  // namespace cupola

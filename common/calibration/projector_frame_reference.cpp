#include "calibration/projector_frame_reference.hpp"

#include <algorithm>
#include <cmath>

namespace cupola {

namespace {
glm::dvec2 grid_uv(const WarpGrid& g, int i, int j) { return g.uv[static_cast<size_t>(j) * g.columns + i]; }

bool is_nan(const glm::dvec2& v) { return std::isnan(v.x) || std::isnan(v.y); }

glm::vec4 sample_render(const Image& img, const glm::dvec2& uv) {
    // Texel centres at (x + 0.5) / width; v up: row 0 (top) is v = 1.
    const double fx = uv.x * img.width - 0.5, fy = (1.0 - uv.y) * img.height - 0.5;
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    const double tx = fx - x0, ty = fy - y0;
    auto at = [&](int x, int y) {
        const float* p = img.pixel(std::clamp(x, 0, img.width - 1), std::clamp(y, 0, img.height - 1));
        return glm::vec4(p[0], p[1], p[2], p[3]);
    };
    const glm::vec4 top = glm::mix(at(x0, y0), at(x0 + 1, y0), static_cast<float>(tx));
    const glm::vec4 bottom = glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), static_cast<float>(tx));
    return glm::mix(top, bottom, static_cast<float>(ty));
}

float encode(double linear, double gamma, int bits) {
    double v = std::pow(std::clamp(linear, 0.0, 1.0), 1.0 / gamma);
    if (bits > 0) {
        const double levels = std::ldexp(1.0, bits) - 1.0;
        v = std::round(v * levels) / levels;
    }
    return static_cast<float>(v);
}
}  // namespace

std::optional<glm::dvec2> sample_warp_grid(const ProjectorWarp& warp, const glm::dvec2& pixel) {
    const WarpGrid& g = warp.grid;
    if (g.columns < 2 || g.rows < 2) return std::nullopt;
    const double gx = std::clamp(pixel.x * g.columns / warp.raster_width - 0.5, 0.0, g.columns - 1.0);
    const double gy = std::clamp(pixel.y * g.rows / warp.raster_height - 0.5, 0.0, g.rows - 1.0);
    const int i = std::min(static_cast<int>(gx), g.columns - 2), j = std::min(static_cast<int>(gy), g.rows - 2);
    const double tx = gx - i, ty = gy - j;
    const glm::dvec2 a = grid_uv(g, i, j), b = grid_uv(g, i + 1, j), c = grid_uv(g, i, j + 1),
                     d = grid_uv(g, i + 1, j + 1);
    if (is_nan(a) || is_nan(b) || is_nan(c) || is_nan(d)) return std::nullopt;
    const glm::dvec2 uv = (1.0 - ty) * ((1.0 - tx) * a + tx * b) + ty * ((1.0 - tx) * c + tx * d);
    if (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0) return std::nullopt;
    return uv;
}

double sample_blend_map(const BlendMap& map, int raster_width, int raster_height, const glm::dvec2& pixel,
                        double fallback) {
    if (map.empty()) return fallback;
    const double fx = std::clamp(pixel.x * map.width / raster_width - 0.5, 0.0, map.width - 1.0);
    const double fy = std::clamp(pixel.y * map.height / raster_height - 0.5, 0.0, map.height - 1.0);
    const int x0 = std::min(static_cast<int>(fx), map.width - 1), y0 = std::min(static_cast<int>(fy), map.height - 1);
    const int x1 = std::min(x0 + 1, map.width - 1), y1 = std::min(y0 + 1, map.height - 1);
    const double tx = fx - x0, ty = fy - y0;
    auto at = [&](int x, int y) { return static_cast<double>(map.value[static_cast<size_t>(y) * map.width + x]); };
    return (1.0 - ty) * ((1.0 - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1.0 - tx) * at(x0, y1) + tx * at(x1, y1));
}

Image reference_projector_frame(const ProjectorWarp& warp, const Image& channel_render,
                                const ProjectorFrameOptions& options) {
    Image out;
    out.width = warp.raster_width;
    out.height = warp.raster_height;
    out.rgba.assign(static_cast<size_t>(out.width) * out.height * 4, 0.0f);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            const glm::dvec2 p(x + 0.5, y + 0.5);
            const auto uv = sample_warp_grid(warp, p);
            const glm::vec4 c = uv ? sample_render(channel_render, *uv) : glm::vec4(0.0f);
            const double alpha = options.blend ? sample_blend_map(warp.alpha, out.width, out.height, p, 1.0) : 1.0;
            const double beta = options.blend ? sample_blend_map(warp.beta, out.width, out.height, p, 0.0) : 0.0;
            float* o = out.pixel(x, y);
            for (int k = 0; k < 3; ++k)
                o[k] = encode(c[k] * alpha * (1.0 - beta) + beta, warp.projector_gamma, options.quantize_bits);
            o[3] = 1.0f;
        }
    return out;
}

}  // namespace cupola

#include "calibration/projector_frame_reference.hpp"

#include <algorithm>
#include <cmath>

#include "calibration/reference_warp.hpp"

namespace cupola {

namespace {
float encode(double linear, double gamma, int bits) {
    double v = std::pow(std::clamp(linear, 0.0, 1.0), 1.0 / gamma);
    if (bits > 0) {
        const double levels = std::ldexp(1.0, bits) - 1.0;
        v = std::round(v * levels) / levels;
    }
    return static_cast<float>(v);
}

LinearImage rgb_of(const Image& img) {
    LinearImage out{img.width, img.height, 3, std::vector<float>(static_cast<size_t>(img.width) * img.height * 3)};
    for (size_t p = 0; p < static_cast<size_t>(img.width) * img.height; ++p)
        for (int c = 0; c < 3; ++c) out.data[p * 3 + c] = img.rgba[p * 4 + c];
    return out;
}
}  // namespace

std::optional<glm::dvec2> sample_warp_grid(const ProjectorWarp& warp, const glm::dvec2& pixel) {
    const glm::dvec2 uv = warp_uv_at(warp, pixel.x, pixel.y);
    if (!std::isfinite(uv.x + uv.y) || uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0) return std::nullopt;
    return uv;
}

Image reference_projector_frame(const ProjectorWarp& warp, const Image& channel_render,
                                const ProjectorFrameOptions& options) {
    ProjectorWarp used = warp;
    if (!options.blend) used.alpha = {}, used.beta = {}, used.grid.intensity.clear();
    const LinearImage linear = reference_warp(used, rgb_of(channel_render));
    Image out;
    out.width = linear.width;
    out.height = linear.height;
    out.rgba.assign(static_cast<size_t>(out.width) * out.height * 4, 1.0f);
    for (size_t p = 0; p < static_cast<size_t>(out.width) * out.height; ++p)
        for (int c = 0; c < 3; ++c)
            out.rgba[p * 4 + c] = encode(linear.data[p * 3 + c], warp.projector_gamma, options.quantize_bits);
    return out;
}

}  // namespace cupola

#include "calibration/projector_stitch.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "projection/fisheye.hpp"

namespace cupola {

glm::dvec3 projector_light(const IdealProjector& projector, const Image& frame, double gamma, const glm::dvec2& p) {
    if (!projector.lit(p)) return glm::dvec3(0.0);
    const double fx = p.x - 0.5, fy = p.y - 0.5;
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    const double tx = fx - x0, ty = fy - y0;
    auto light = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= frame.width || y >= frame.height) return glm::dvec3(0.0);
        const float* v = frame.pixel(x, y);
        return glm::dvec3(std::pow(v[0], gamma), std::pow(v[1], gamma), std::pow(v[2], gamma));
    };
    return (1.0 - ty) * ((1.0 - tx) * light(x0, y0) + tx * light(x0 + 1, y0)) +
           ty * ((1.0 - tx) * light(x0, y0 + 1) + tx * light(x0 + 1, y0 + 1));
}

glm::dvec3 dome_light(const std::vector<IdealProjector>& projectors, const std::vector<Image>& frames,
                      const std::vector<double>& gammas, const glm::dvec3& dome_dir) {
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < projectors.size(); ++i) {
        if (!projectors[i].on_screen(dome_dir)) continue;
        const auto p = projectors[i].dome_direction_to_pixel(dome_dir);
        if (p) sum += projector_light(projectors[i], frames[i], gammas[i], *p);
    }
    return sum;
}

Image stitch_projector_frames(const std::vector<IdealProjector>& projectors, const std::vector<Image>& frames,
                              const std::vector<double>& gammas, int size) {
    if (frames.size() != projectors.size() || gammas.size() != projectors.size())
        throw std::invalid_argument("stitch_projector_frames: one frame and one gamma per projector");
    const FisheyeMapping fisheye(180.0);
    Image out;
    out.width = out.height = size;
    out.rgba.assign(static_cast<size_t>(size) * size * 4, 0.0f);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const auto dir = fisheye.uv_to_direction(FisheyeMapping::pixel_to_uv({x + 0.5, y + 0.5}, size));
            if (!dir) continue;
            const glm::dvec3 light = dome_light(projectors, frames, gammas, *dir);
            float* o = out.pixel(x, y);
            for (int k = 0; k < 3; ++k) o[k] = static_cast<float>(light[k]);
            o[3] = 1.0f;
        }
    return out;
}

}  // namespace cupola

#include "dome/acuity_blur.hpp"

#include <algorithm>
#include <cmath>

#include "dome/domemaster_stitcher.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

std::optional<glm::dvec3> ChannelRays::direction(const glm::dvec2& pixel) const {
    return frustum_.pixel_to_dome_direction(pixel);
}

std::optional<glm::dvec2> ChannelRays::pixel(const glm::dvec3& direction) const {
    return frustum_.dome_direction_to_pixel(direction);
}

std::optional<glm::dvec3> DomemasterRays::direction(const glm::dvec2& pixel) const {
    return fisheye_.uv_to_direction(FisheyeMapping::pixel_to_uv(pixel, size_));
}

std::optional<glm::dvec2> DomemasterRays::pixel(const glm::dvec3& direction) const {
    const auto uv = fisheye_.direction_to_uv(direction);
    if (!uv) return std::nullopt;
    return FisheyeMapping::uv_to_pixel(*uv, size_);
}

namespace {

bool on_image(const Image& image, const glm::dvec2& p) {
    return p.x >= 0.0 && p.y >= 0.0 && p.x <= image.width && p.y <= image.height;
}

// The blurred value of one pixel looking along d: its taps' weighted mean over those on the image.
void blur_pixel(const Image& linear, const PixelRays& rays, const glm::dvec3& d, float sigma_rad, float out[4]) {
    double sum[4] = {0.0, 0.0, 0.0, 0.0};
    double weight = 0.0;
    for (int k = 0; k < shading::ACUITY_TAPS; ++k) {
        const glm::vec3 dir = shading::acuity_tap_direction(glm::vec3(d), sigma_rad, k);
        const auto p = rays.pixel(glm::dvec3(dir));
        if (!p || !on_image(linear, *p)) continue;
        const double w = shading::acuity_tap(k).z;
        float s[4];
        sample_bilinear(linear, p->x, p->y, s);
        for (int c = 0; c < 4; ++c) sum[c] += w * s[c];
        weight += w;
    }
    if (!(weight > 0.0)) return;  // no tap on the image: keep the pixel's own value
    for (int c = 0; c < 4; ++c) out[c] = static_cast<float>(sum[c] / weight);
}

Image blur_pass(const Image& linear, const PixelRays& rays, double sigma_rad) {
    Image out = linear;
    for (int y = 0; y < linear.height; ++y) {
        for (int x = 0; x < linear.width; ++x) {
            const auto d = rays.direction(glm::dvec2(x + 0.5, y + 0.5));
            if (d) blur_pixel(linear, rays, *d, static_cast<float>(sigma_rad), out.pixel(x, y));
        }
    }
    return out;
}

// The angle one pixel spans at the image's centre.
double centre_rad_per_px(const Image& image, const PixelRays& rays) {
    const glm::dvec2 c(image.width * 0.5, image.height * 0.5);
    const auto a = rays.direction(c), b = rays.direction(c + glm::dvec2(1.0, 0.0));
    if (!a || !b) return 0.0;
    return std::acos(std::clamp(glm::dot(*a, *b), -1.0, 1.0));
}

}  // namespace

int acuity_blur_passes(double sigma_rad, double rad_per_px) {
    if (!(sigma_rad > 0.0) || !(rad_per_px > 0.0)) return 1;
    const double ratio = sigma_rad / rad_per_px / kAcuityPassMaxPx;
    return std::clamp(static_cast<int>(std::ceil(ratio * ratio)), 1, 64);
}

Image acuity_blurred(const Image& linear, const PixelRays& rays, double sigma_rad) {
    if (!(sigma_rad > 0.0)) return linear;
    const int passes = acuity_blur_passes(sigma_rad, centre_rad_per_px(linear, rays));
    Image out = blur_pass(linear, rays, sigma_rad / std::sqrt(passes));
    for (int k = 1; k < passes; ++k) out = blur_pass(out, rays, sigma_rad / std::sqrt(passes));
    return out;
}

}  // namespace cupola

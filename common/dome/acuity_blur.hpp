#pragma once
// The eye's loss of acuity at night on the CPU: the display transform of the stitched domemaster's
// PNG (and of any image whose pixels have known directions) blurs the linear image with the
// Gaussian of shaders/shared/night_acuity.glsl, taken in angle on the sky: 13 taps around each
// pixel's direction, mapped back into the image and sampled bilinearly. Because the taps are
// directions, the blur is as wide in degrees wherever the image's pixels are small or large, and
// two images of the same sky (two channels, or a channel and the domemaster) blur it alike. The
// projector outputs run the same taps on the GPU (shaders/warp.frag).
#include <glm/glm.hpp>

#include <optional>

#include "image/frame_image.hpp"
#include "projection/channel_frustum.hpp"
#include "projection/fisheye.hpp"

namespace cupola {

// Where an image's pixels look: continuous pixel coordinates (x right, y down, (0, 0) the top-left
// corner) to and from unit directions in one frame.
class PixelRays {
public:
    virtual ~PixelRays() = default;
    // Nothing where the pixel shows no sky (outside a fisheye's circle).
    virtual std::optional<glm::dvec3> direction(const glm::dvec2& pixel) const = 0;
    // Nothing where the image has no pixel for the direction (behind a channel's plane, beyond the
    // fisheye's field).
    virtual std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const = 0;
};

// A channel's perspective frustum (dome frame).
class ChannelRays final : public PixelRays {
public:
    explicit ChannelRays(ChannelFrustum frustum) : frustum_(std::move(frustum)) {}
    std::optional<glm::dvec3> direction(const glm::dvec2& pixel) const override;
    std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const override;

private:
    ChannelFrustum frustum_;
};

// A size x size domemaster (the untilted dome frame).
class DomemasterRays final : public PixelRays {
public:
    DomemasterRays(double fov_deg, int size) : fisheye_(fov_deg), size_(size) {}
    std::optional<glm::dvec3> direction(const glm::dvec2& pixel) const override;
    std::optional<glm::dvec2> pixel(const glm::dvec3& direction) const override;

private:
    FisheyeMapping fisheye_;
    int size_;
};

// Below this blur (its standard deviation in pixels at the image's coarsest pixel scale, as
// acuity_blur_needed measures it) the display transforms leave the image as it is: a quarter of
// a pixel widens a point by under 3 % of a pixel's area.
constexpr double kAcuityBlurMinPx = 0.25;

// Whether a blur of sigma_rad is worth drawing on an image whose pixels are at most
// rad_per_px wide.
inline bool acuity_blur_needed(double sigma_rad, double rad_per_px) {
    return sigma_rad > 0.0 && rad_per_px > 0.0 && sigma_rad / rad_per_px >= kAcuityBlurMinPx;
}

// The 13 taps stand for a Gaussian as long as they are at most about two pixels apart, that is
// up to sigma = 1.5 px; a point blurred wider shows them as a ring of dots. A wider blur is taken
// in n passes of sigma / sqrt(n) (Gaussians compose by adding their variances): n =
// ceil((sigma_px / 1.5)^2), at most 64.
constexpr double kAcuityPassMaxPx = 1.5;
int acuity_blur_passes(double sigma_rad, double rad_per_px);

// The linear image blurred by the eye's acuity: each pixel the weighted mean of its 13 taps that
// land on the image (weights renormalised over those; a tap off the image is left out, as the
// sky beyond a channel's edge is not in it), in as many passes as the blur's width at the
// image's centre needs. Pixels without a direction are copied. sigma_rad <= 0 returns the image
// unchanged.
Image acuity_blurred(const Image& linear, const PixelRays& rays, double sigma_rad);

}  // namespace cupola

#pragma once
// The projector pass: draws one projector's raster from the channel's render through its
// calibration (common/calibration/projector_warp.hpp), multiplies the blend, lifts the black level
// and encodes with the projector's gamma (shaders/warp.frag, shaders/shared/projector_blend.glsl).
//
// How the warp is drawn: a per-pixel lookup, not a mesh. One full-screen triangle
// (shaders/fullscreen.vert); each fragment
// finds its raster position, reads the four surrounding grid points (an RGBA32F texture holding
// u, v and the intensity, texelFetch) and interpolates them bilinearly in fp32 in the shader.
//  - The contract says the grid is interpolated bilinearly; a triangulated mesh interpolates
//    linearly per triangle, which differs from it inside every cell that is not a parallelogram;
//    the lookup is the contract's bilinear rule exactly.
//  - Hardware bilinear filtering of the grid texture would be cheaper but keeps only 8 bits of
//    sub-texel weight on common GPUs: over a 32x32 grid on a 2048-texel channel that is a quarter
//    of a content texel of error. The shader weights the four points in fp32 instead.
//  - About one cost for every grid size, from 2x2 (MPCDI geometry level 1) to per-pixel (level
//    2): 32x32 and per-pixel differ by ~15 % (BENCHMARKS.md, "Projector warp pass").
//  - Between the outer grid centres and the raster's edge (half a cell in fill layout) the edge
//    value holds, as in the CPU reference (common/calibration/reference_warp.hpp) and in readers
//    that sample the warp as a clamped texture. No calibration (nullopt) skips the grid: the
//    raster is the content, pixel for pixel.
//  - A pixel shows black content when any of its four grid points is NaN (the rule a mesh that
//    skips cells with a NaN corner follows), or when its (u, v) lies outside [0, 1] (no content
//    there); the blend still lifts it to beta, as every pixel.
//
// Supersampling: when one projector pixel covers more than one content texel (a 2048^2 channel
// onto a 1920x1200 raster), a single bilinear tap aliases (moire on fine detail). The shader takes
// the analytic Jacobian of the bilinear warp, d(u,v)/d(pixel), and averages an n x n box of
// bilinear taps over the pixel's footprint (the parallelogram the Jacobian maps the pixel onto),
// n = ceil(the footprint's longer side in texels), at most WarpOptions::supersample_filter (1: one
// tap, no filter). Where a pixel covers one texel or less (identity, magnification), n = 1. The
// content's own texture state is left alone: the pass samples it through its own sampler object
// (bilinear, clamped to the edge), so single-level, nearest-filtered render targets work as given.
// Measured against the CPU area average of a one-texel checker: WarpPass.FootprintFilter... in
// tests/test_warp_pass.cpp and benchmarks/warp_cost.cpp (BENCHMARKS.md).
//
// Blend maps: alpha and beta are float textures over the whole raster, sampled bilinearly at the
// pixel centre (any size). The per-point intensity of a Bourke mesh is interpolated with u, v.
// Content after exposure goes through the display curve of the frame's white (shaders/shared/
// tone_curve.glsl; none at a fixed exposure), then into the projector's range by the gamut map.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "calibration/projector_warp.hpp"
#include "image/frame_image.hpp"
#include "projection/channel_frustum.hpp"

namespace cupola {

struct WarpOptions {
    // Srgb: the IEC 61966-2-1 curve (a monitor); Gamma: value = C_out^(1 / projector_gamma).
    enum class Encode { Srgb, Gamma } encode = Encode::Gamma;
    // The most taps per axis of the footprint box filter (1..8); 1 turns the filter off.
    int supersample_filter = 4;
    // The content's projection (the channel's frustum), which the eye's acuity blur at night needs
    // to take its taps in angle (shaders/shared/night_acuity.glsl); without it there is no blur.
    std::optional<ChannelFrustum> content_view;
};

class WarpPass {
public:
    // warp == nullopt: identity (projector raster = content size, alpha 1, beta 0), sRGB encode
    // (whatever options.encode says). Throws std::invalid_argument naming warp->source when the
    // warp is malformed (grid smaller than 2x2 or of the wrong size, empty raster, maps whose
    // sizes do not match their values), and std::runtime_error for GL failures.
    WarpPass(std::optional<ProjectorWarp> warp, int content_width, int content_height, WarpOptions options = {});
    ~WarpPass();
    WarpPass(const WarpPass&) = delete;
    WarpPass& operator=(const WarpPass&) = delete;

    // Needs a current GL 4.5 context. Draws the projector raster from the content texture (GL
    // texture name of linear RGBA32F radiance, v up: GL's row 0 at the bottom) times exposure into
    // two targets: linear (RGBA32F, after alpha and beta, before encode) and encoded (RGBA8, for
    // the projector), through the eye's night vision at night_adapted_cd_m2 (0: none) and the
    // display curve of white `tone_white` (0: none), blurred first by the eye's acuity of standard
    // deviation acuity_sigma_rad (0: none; needs options.content_view; skipped under a quarter
    // of a content pixel, common/dome/acuity_blur.hpp). Leaves the draw framebuffer bound to the
    // encoded target.
    void draw(unsigned content_texture, double exposure, double tone_white = 0.0, double night_adapted_cd_m2 = 0.0,
              double acuity_sigma_rad = 0.0);

    unsigned linear_framebuffer() const;
    unsigned encoded_framebuffer() const;
    unsigned linear_texture() const;   // GL texture name of the linear target (RGBA32F)
    unsigned encoded_texture() const;  // GL texture name of the encoded target (RGBA8)
    int width() const;
    int height() const;

    Image read_linear() const;                  // RGBA float, row 0 top
    std::vector<uint8_t> read_encoded() const;  // RGBA8, row 0 top

private:
    void set_acuity_blur(double sigma_rad) const;

    struct Gpu;
    std::optional<ProjectorWarp> warp_;
    int width_ = 0, height_ = 0;
    int content_width_ = 0, content_height_ = 0;
    WarpOptions options_;
    std::unique_ptr<Gpu> gpu_;
};

}  // namespace cupola

#pragma once
// The star field. Sizes and brightness are angular and cluster-wide (StarFieldConfig);
// see shaders/stars.{vert,frag} and shaders/shared/star_psf.glsl.
#include <memory>
#include <vector>

#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "passes/channel_view.hpp"
#include "passes/beyond_the_air.hpp"
#include "passes/star_sky.hpp"
#include "passes/star_sky_weights.hpp"
#include "scene/star_catalog.hpp"

namespace cupola {

// The body that hides the most sky from the stars: its centre direction (unit, channel frame) and
// angular radius; none when radius_rad <= 0.
struct StarOccluder {
    glm::vec3 center_dir{0.0f, 0.0f, -1.0f};
    float radius_rad = 0.0f;
};

// The stars' twinkling in one frame (shaders/shared/star_twinkle.glsl), the same on every
// channel: from the snapshot's mode and clock and the air the camera stands in.
struct StarTwinkle {
    float sigma_zenith = 0.0f;     // 0: no twinkling
    glm::vec3 zenith_world{0.0f};  // unit; zero: every star at airmass 1
    float time_s = 0.0f;           // the snapshot's twinkle clock
};

class StarPass : public BeyondTheAirPass {
public:
    // stars: any order (sorted here by magnitude so a limit is a prefix).
    StarPass(const StarFieldConfig& config, std::vector<Star> stars);
    // Adds the stars brighter than magnitude_limit into the bound framebuffer, each over the
    // pixels where its PSF can reach kMinDisplay at this exposure (stars.vert; exposure <= 0:
    // the PSF out to kFixedReachSigma for every star). A star whose sprite lies wholly behind the
    // occluder (which the body pass, or its atmosphere relighting the ground, then paints over,
    // opaque) is not drawn. With a sky (StarSky::table), each star shows only as far as the eye
    // could see it against the sky behind it (shared/star_visibility.glsl): fading in over half a
    // magnitude above the threshold, not drawn below it; the table is brought up to date first.
    // after_sky (with a sky): the sky was drawn first, and each star also takes the air's
    // transmittance in front of it (beyond_the_air.hpp).
    void draw(const ChannelView& view, double magnitude_limit, double exposure = 0.0, StarOccluder occluder = {},
              const StarSky& sky = {}, bool after_sky = false);
    // The largest body on screen of a frame, not a star and not around the camera.
    static StarOccluder largest_occluder(const FrameContext& frame);
    // The twinkling of a frame: mode on twinkles by the airmass when the camera is inside the
    // air of `sky`; forced also does so, and without air twinkles every star as at the zenith.
    static StarTwinkle twinkle_for(const Snapshot& snap, const StarSky& sky);
    // What draw() twinkles with (prepare_at sets it from the frame).
    void set_twinkle(const StarTwinkle& t) { twinkle_ = t; }
    static constexpr double kFixedReachSigma = 4.0;

    // In the pass list: additive, colour only (the G-buffer stays "nothing drawn"); the stars
    // brighter than the scene's and the snapshot's magnitude limits and than visible_magnitude()
    // at the snapshot's exposure (cluster-wide, so every channel draws the same stars), and of
    // those the ones the eye could see against the sky of the sky source (set_sky_source), star
    // by star. Skipped (0 draws) when no star is left.
    std::string name() const override { return "stars"; }
    PassIo io() const override { return {.writes_color = true}; }
    int prepare_at(const FrameContext& frame, bool after_sky) override;
    void draw(const PassInputs& in, int step) override;

    // The faintest magnitude whose PSF peak (flux / (2 pi sigma^2), the Gaussian's centre) reaches
    // kMinDisplay on the display at this exposure; fainter stars cannot change an 8-bit pixel.
    double visible_magnitude(double exposure) const;
    static constexpr double kMinDisplay = 1.0 / 8192.0;  // under half of the first sRGB code value
    // Where the sky behind the stars comes from (the atmosphere pass); none: the exposure alone.
    void set_sky_source(const StarSkySource* source) { sky_source_ = source; }
    long sky_weight_renders() const { return sky_weights_->renders(); }

private:
    StarFieldConfig config_;
    std::vector<float> magnitudes_;  // ascending
    GlProgram program_;
    GlVertexBuffer vertices_;
    const ChannelView* view_ = nullptr;
    double magnitude_limit_ = 0.0;
    double exposure_ = 0.0;
    StarOccluder occluder_;
    std::unique_ptr<StarSkyWeights> sky_weights_;  // one texel per star, in vertex order
    const StarSkySource* sky_source_ = nullptr;
    StarSky sky_;
    bool after_sky_ = false;
    StarTwinkle twinkle_;
};

}  // namespace cupola

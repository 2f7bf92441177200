#pragma once
// What lies beyond a planet's air (the stars, the Sun, the other bodies) is drawn in one of two
// places in a frame:
//   before the atmosphere (the usual order): into the cleared colour; the atmosphere's draw then
//     multiplies what is there by the air's transmittance and adds its own light;
//   after it, when the sky is drawn first (FrameContext::sky_first: the camera inside the air of
//     the only atmosphere in view, which draws its own ground, AtmospherePass::sky_first): the
//     sky and the ground are written over the whole channel without a clear and without reading
//     the colour, and each draw beyond the air takes the air in front of it from the same
//     sky-view table itself (shared/atmosphere_sky_view.glsl, atm_sky_in_front_*): a star its
//     weight times the transmittance (star_weights.frag), the Sun's disc and corona the
//     transmittance, a moon the transmittance and the in-scatter (it replaces the sky).
// One pass object draws in either place. It stands in the pass list before the atmosphere, and
// an AfterTheSky entry after the atmosphere stands for it there; each frame exactly one of the two
// draws. The result is the same image up to float rounding, except that a star's sprite takes one
// transmittance (at its centre) instead of one per pixel.
#include <string>

#include "gl/gl_program.hpp"
#include "passes/render_pass.hpp"

namespace cupola {

// Who sets what a draw beyond the air needs in a frame whose sky was drawn first: u_atm, u_sky
// (SkyInFront), the sky-view table's parts as u_sky_phased, u_sky_mie, u_sky_third, the glare
// halo the sky's draw added (u_halo_on, u_halo, u_halo_map), and with a moonlit sky the Moon's
// table's first two parts as u_sky_moon_phased, u_sky_moon_mie (common/atmosphere/moonlit_sky.hpp). The
// atmosphere pass.
class SkyInFrontSource {
public:
    virtual ~SkyInFrontSource() = default;
    // Binds the textures to units kFirstUnit .. kFirstUnit + 6 (the Moon's table the last three;
    // units up to 18: every GL 4.5 driver Cupola runs on has 32 per stage) and sets p's uniforms (p in use).
    virtual void set_sky_in_front(const GlProgram& p) const = 0;
    static constexpr unsigned kFirstUnit = 12;
};

// A pass that draws what lies beyond the air, before the atmosphere or after it.
class BeyondTheAirPass : public RenderPass {
public:
    // In its own place, before the atmosphere: nothing in a frame whose sky is drawn first.
    int prepare(const FrameContext& frame) final { return frame.sky_first ? 0 : prepare_at(frame, false); }
    // after_sky: the frame's sky was drawn first, and the draws take the air in front themselves.
    virtual int prepare_at(const FrameContext& frame, bool after_sky) = 0;
};

// The entry after the atmosphere that stands for a BeyondTheAirPass: it draws only in a frame
// whose sky is drawn first, into the colour alone (no G-buffer: nothing after it reads one).
class AfterTheSky final : public RenderPass {
public:
    explicit AfterTheSky(BeyondTheAirPass& pass) : pass_(pass) {}
    std::string name() const override { return pass_.name() + " after the sky"; }
    PassIo io() const override { return {.writes_color = true}; }
    int prepare(const FrameContext& frame) override { return frame.sky_first ? pass_.prepare_at(frame, true) : 0; }
    void draw(const PassInputs& in, int step) override { pass_.draw(in, step); }
    bool reads_geometry_in(const FrameContext&) const override { return false; }

private:
    BeyondTheAirPass& pass_;
};

}  // namespace cupola

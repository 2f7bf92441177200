#pragma once
// The planets, moons and the Sun that show as points this frame (PlanetLight::has_point, decided
// once per frame for the whole cluster in the frame context): each drawn with the stars' PSF,
// widened by its disc's size, carrying (1 - disc weight) of its light, added after the discs so
// that the point's light under a fading disc is not painted over. Hidden per pixel behind up to
// four nearer bodies; the Sun's point instead carries the part of its disc they leave visible.
// Beyond the air: before the atmosphere, or after a sky drawn first with the air's transmittance
// in front (beyond_the_air.hpp). A point whose largest sprite (255 pixels, plus the guard band)
// cannot reach the channel, or whose peak the exposure cannot show, is not drawn: 0 draws when
// none is left.
#include <vector>

#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "passes/beyond_the_air.hpp"

namespace cupola {

class PlanetPointPass : public BeyondTheAirPass {
public:
    PlanetPointPass();
    std::string name() const override { return "planet points"; }
    PassIo io() const override { return {.writes_color = true}; }
    int prepare_at(const FrameContext& frame, bool after_sky) override;
    void draw(const PassInputs& in, int step) override;
    // Where the air in front comes from when the sky was drawn first (the atmosphere pass).
    void set_sky_in_front(const SkyInFrontSource* sky) { sky_ = sky; }
    static constexpr int kMaxOccluders = 4;
    // Whether the point's PSF peak can reach StarPass::kMinDisplay at the snapshot's exposure (as
    // the stars' visible_magnitude; exposure <= 0: always). A planet by day is not drawn.
    static bool visible_at(const PlanetLight& light, double exposure);
    // Points drawn since construction (a point is drawn only when its sprite can reach the channel).
    long points_drawn() const { return points_drawn_; }

private:
    void draw_point(const GlProgram& program, const FrameBody& body) const;
    void set_occluders(const GlProgram& program, const FrameBody& body) const;
    GlProgram program_, after_sky_program_;
    GlEmptyVertexArray vao_;
    const FrameContext* frame_ = nullptr;
    std::vector<const FrameBody*> in_view_;  // this frame's points whose sprite can reach the channel
    long points_drawn_ = 0;
    bool after_sky_ = false;
    const SkyInFrontSource* sky_ = nullptr;
};

}  // namespace cupola

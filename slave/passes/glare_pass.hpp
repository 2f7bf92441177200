#pragma once
// The glare, last in the pass list: every source the master shares (snapshot.glare), on a
// viewpoint-oriented billboard per source -- its normal points at the shared camera position,
// its axes are the cluster-wide glare frame (common/glare/glare_frame), its size the glare's
// angular extent -- drawn without depth test, added to the HDR image. Every channel draws every
// source, also where the source itself is out of its frustum, from the shared visible fraction;
// in per-channel mode (the naive comparison) only while the source's centre is in its own
// frustum, from its own query.
#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "passes/glare_probe.hpp"
#include "passes/render_pass.hpp"
#include "passes/sphere_billboard.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

class GlarePass : public RenderPass {
public:
    // probe: this channel's measurements, for the per-channel mode.
    GlarePass(const SceneConfig& scene, const GlareProbe& probe);
    // Draws into the bound colour target (attachment 0).
    void draw(const ChannelView& view, const Snapshot& snap, const GlareProbe& probe);

    // In the pass list: additive, colour only, when the snapshot has glare sources.
    std::string name() const override { return "glare"; }
    PassIo io() const override { return {.writes_color = true}; }
    int prepare(const FrameContext& frame) override;
    void draw(const PassInputs& in, int step) override;

    // The angle beyond which a source's glare stays below a quarter of glare.min_display on the
    // dome (at most glare.extent_deg): fainter sources get smaller billboards.
    double extent_rad(const GlareSource& source, double exposure) const;

    long sources_drawn() const { return drawn_; }

private:
    const SceneConfig* scene_;
    const GlareProbe& probe_;
    const FrameContext* frame_ = nullptr;
    GlProgram program_;
    GlEmptyVertexArray vao_;
    long drawn_ = 0;
};

}  // namespace cupola

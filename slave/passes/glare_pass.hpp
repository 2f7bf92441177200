#pragma once
// The glare, last in the pass list: every source the master shares (snapshot.glare), placed by
// glare_placement.hpp, added to the HDR image without depth test. Two ways, the same PSF
// (shared/glare_psf.glsl):
//   - split (glare.halo_downsample 2, 4 or 8; with a GlareHaloPass before this pass): the halo
//     target upsampled over the channel, then per source its core on a billboard only as large
//     as the core, and its rays as one thin triangle each (glare_halo_pass.hpp has the split);
//   - full resolution (halo_downsample 1): per source, the whole PSF per pixel on a
//     viewpoint-oriented billboard -- its normal toward the shared camera position, its axes the
//     cluster-wide glare frame (common/glare/glare_frame), its size the glare's angular extent.
#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "passes/glare_halo_pass.hpp"
#include "passes/glare_placement.hpp"
#include "passes/glare_probe.hpp"
#include "passes/render_pass.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

class GlarePass : public RenderPass {
public:
    // probe: this channel's measurements, for the per-channel mode. halo: the halo pass before
    // this one (split way), or null (full resolution).
    GlarePass(const SceneConfig& scene, const GlareProbe& probe, const GlareHaloPass* halo);

    // In the pass list: additive, colour only, when a glare source reaches the channel.
    std::string name() const override { return "glare"; }
    PassIo io() const override { return {.writes_color = true}; }
    int prepare(const FrameContext& frame) override;
    void draw(const PassInputs& in, int step) override;

    long sources_drawn() const { return drawn_; }

private:
    void draw_full(const GlarePlacement& g) const;
    void draw_halo() const;
    void draw_core(const GlarePlacement& g) const;
    void draw_rays(const GlarePlacement& g) const;

    const SceneConfig* scene_;
    const GlareProbe& probe_;
    const GlareHaloPass* halo_;
    const FrameContext* frame_ = nullptr;
    std::vector<GlarePlacement> placements_;
    GlProgram full_, upsample_, core_, rays_;
    GlEmptyVertexArray vao_;
    long drawn_ = 0;
};

}  // namespace cupola

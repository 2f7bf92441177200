#pragma once
// The glare's wide, smooth halo at reduced resolution, before the atmosphere and the glare pass
// (glare_pass.hpp) in the pass list. The glare PSF (Spencer et al. 1995, shared/glare_psf.glsl) is split three
// ways, which sum to it exactly:
//   - the core: the part without azimuth (glare_psf_smooth) near the source, where it is steep,
//     fading out (glare_core_share) between core_rad().x and .y (at least kCoreTexels halo
//     texels: 10.7 and 21.5 deg in a 512-pixel, 90-degree channel at 1/4) -- drawn at full
//     resolution by the glare pass on a billboard only as large as the core;
//   - the halo: the rest of that part, zero near the source and slowly varying beyond -- drawn
//     here into a target of its own at 1/glare.halo_downsample of the resolution per axis
//     (GlareHaloGrid, with a guard band beyond the channel's edges), and added by the glare pass
//     with bilinear upsampling;
//   - the rays of the ciliary corona: drawn at full resolution by the glare pass, as one thin
//     triangle per ray, only where they are nonzero.
// The core reaches at least kCoreTexels halo texels, so the halo's curvature within a texel is
// small against its value (the interpolation error, tests/test_glare_halo.cpp), and past the
// lenticular ring, which stays at full resolution.
#include <memory>
#include <vector>

#include "config/scene_config.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/glare_halo_grid.hpp"
#include "passes/glare_placement.hpp"
#include "passes/glare_probe.hpp"
#include "passes/render_pass.hpp"

namespace cupola {

class GlareHaloPass : public RenderPass {
public:
    static constexpr double kCoreTexels = 12.0;  // the core's inner angle, in halo texels at the axis

    GlareHaloPass(const SceneConfig& scene, const GlareProbe& probe);

    // In the pass list: draws into its own target, none of the frame's; runs when some glare
    // source reaches the channel.
    std::string name() const override { return "glare halo"; }
    PassIo io() const override { return {}; }
    int prepare(const FrameContext& frame) override;
    void draw(const PassInputs& in, int step) override;

    // This frame's sources (set by prepare), and what the glare pass needs to add their halo.
    const std::vector<GlarePlacement>& placements() const { return placements_; }
    const GlareHaloGrid& grid() const { return grid_; }
    const GlTexture& texture() const { return *texture_; }
    // The core's inner and outer angle: the halo has none of the PSF inside the inner one.
    glm::vec2 core_rad() const { return core_rad_; }
    // Whether this frame's target holds any halo (some source reaches past its core).
    bool has_halo() const;
    // The halo is added to the colour by whichever pass comes first after it: a pass that
    // covers the whole channel anyway (the atmosphere seen from inside, atmosphere_pass.cpp) adds
    // it in the same draw and marks it; otherwise the glare pass upsamples it on its own. Reset
    // by prepare() every frame.
    void mark_composited() const { composited_ = true; }
    bool composited() const { return composited_; }

private:
    void make_target(const ChannelFrustum& frustum);

    const SceneConfig* scene_;
    const GlareProbe& probe_;
    const FrameContext* frame_ = nullptr;
    GlProgram program_;
    GlEmptyVertexArray vao_;
    GlareHaloGrid grid_;
    std::unique_ptr<GlTexture> texture_;
    std::unique_ptr<GlFramebuffer> target_;
    glm::vec2 core_rad_{0.0f};
    std::vector<GlarePlacement> placements_;
    mutable bool composited_ = false;
};

}  // namespace cupola

#include "passes/glare_halo_pass.hpp"

#include <algorithm>

namespace cupola {

GlareHaloPass::GlareHaloPass(const SceneConfig& scene, const GlareProbe& probe)
    : scene_(&scene), probe_(probe), program_("fullscreen.vert", "glare_halo.frag") {}

void GlareHaloPass::make_target(const ChannelFrustum& frustum) {
    const GlareConfig& c = scene_->glare;
    grid_ = GlareHaloGrid::for_channel(frustum, c.halo_downsample);
    texture_ = std::make_unique<GlTexture>(grid_.width, grid_.height, nullptr, GL_LINEAR);
    target_ = std::make_unique<GlFramebuffer>(std::vector<const GlTexture*>{texture_.get()});
    // The lenticular ring (its red radius, shared/glare_psf.glsl's glare_halo, plus 4 sigma)
    // stays in the core.
    const double ring_rad =
        c.halo_fraction > 0.0 ? glm::radians(c.halo_radius_deg * 1.10909091 + 4.0 * c.halo_width_deg) : 0.0;
    const double inner = std::max(kCoreTexels * grid_.texel_rad, ring_rad);
    core_rad_ = glm::vec2(inner, 2.0 * inner);
}

bool GlareHaloPass::has_halo() const {
    return std::any_of(placements_.begin(), placements_.end(),
                       [&](const GlarePlacement& g) { return g.extent_rad > core_rad_.x; });
}

int GlareHaloPass::prepare(const FrameContext& frame) {
    frame_ = &frame;
    composited_ = false;
    if (!target_) make_target(*frame.view.frustum);
    placements_ = place_glare(scene_->glare, frame.view, *frame.snap, probe_);
    return placements_.empty() ? 0 : 1;
}

void GlareHaloPass::draw(const PassInputs&, int) {
    target_->bind();
    target_->clear(0, glm::vec4(0.0f));
    program_.use();
    set_glare_params(program_, scene_->glare, frame_->snap->settings.glare_phase);
    program_.set("u_tangents", grid_.tangents);
    program_.set("u_size", glm::vec2(grid_.width, grid_.height));
    program_.set("u_core_rad", core_rad_);
    program_.set("u_pixel_scale", 1.0f / static_cast<float>(grid_.downsample));
    glEnablei(GL_BLEND, 0);
    glBlendFunci(0, GL_ONE, GL_ONE);
    vao_.bind();
    for (const GlarePlacement& g : placements_) {
        // Nothing of this source's PSF lies outside its core: no halo to draw.
        if (g.extent_rad <= core_rad_.x) continue;
        set_glare_placement(program_, g);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisablei(GL_BLEND, 0);
    gl::check("glare halo pass");
}

}  // namespace cupola

#include "passes/glare_pass.hpp"

#include <algorithm>
#include <cmath>

#include "passes/sphere_billboard.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

namespace {

// The billboard of a glare: in the plane at the scaled distance along its centre, normal
// toward the camera position, a square circumscribing the cone of half-angle `angle_rad`.
SphereView glare_billboard(const GlarePlacement& g, double angle_rad) {
    SphereView quad;
    const double k = SphereView::kScaledDistance;
    const double h = k * std::tan(angle_rad);
    const glm::dvec3 p = g.center * k;
    quad.corners = {glm::vec3(p - h * g.e1 - h * g.e2), glm::vec3(p + h * g.e1 - h * g.e2),
                    glm::vec3(p - h * g.e1 + h * g.e2), glm::vec3(p + h * g.e1 + h * g.e2)};
    quad.center_dir = g.center;
    quad.distance_m = 1.0;
    quad.radius_m = 0.0;
    return quad;
}

}  // namespace

GlarePass::GlarePass(const SceneConfig& scene, const GlareProbe& probe, const GlareHaloPass* halo)
    : scene_(&scene),
      probe_(probe),
      halo_(halo),
      full_("sphere.vert", "glare.frag"),
      upsample_("fullscreen.vert", "glare_upsample.frag"),
      core_("sphere.vert", "glare_core.frag"),
      rays_("glare_rays.vert", "glare_rays.frag") {}

int GlarePass::prepare(const FrameContext& frame) {
    frame_ = &frame;
    placements_ = halo_ ? halo_->placements() : place_glare(scene_->glare, frame.view, *frame.snap, probe_);
    return placements_.empty() ? 0 : 1;
}

void GlarePass::draw(const PassInputs&, int) {
    // Additive in colour; the coverage (alpha) stays what the scene wrote.
    glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    vao_.bind();
    if (halo_) draw_halo();
    for (const GlarePlacement& g : placements_) {
        if (halo_) {
            draw_core(g);
            draw_rays(g);
        } else {
            draw_full(g);
        }
        ++drawn_;
    }
    glDisablei(GL_BLEND, 0);
    gl::check("glare pass");
}

void GlarePass::draw_full(const GlarePlacement& g) const {
    full_.use();
    set_glare_params(full_, scene_->glare, frame_->snap->settings.glare_phase);
    set_glare_placement(full_, g);
    draw_sphere(full_, frame_->view, glare_billboard(g, g.extent_rad));
}

void GlarePass::draw_halo() const {
    if (!halo_->has_halo() || halo_->composited()) return;  // nothing to add, or added with the atmosphere
    upsample_.use();
    halo_->texture().bind(0);
    upsample_.set("u_halo", 0);
    upsample_.set("u_halo_map", halo_->grid().map);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void GlarePass::draw_core(const GlarePlacement& g) const {
    core_.use();
    set_glare_params(core_, scene_->glare, frame_->snap->settings.glare_phase);
    set_glare_placement(core_, g);
    core_.set("u_core_rad", halo_->core_rad());
    draw_sphere(core_, frame_->view, glare_billboard(g, std::min<double>(halo_->core_rad().y, g.extent_rad)));
}

void GlarePass::draw_rays(const GlarePlacement& g) const {
    const GlareConfig& c = scene_->glare;
    if (!(c.streak_contrast > 0.0) || !(c.halo_fraction < 1.0)) return;
    rays_.use();
    set_glare_params(rays_, c, frame_->snap->settings.glare_phase);
    set_glare_placement(rays_, g);
    const double n = std::max(2.0, 2.0 * std::floor(0.5 * c.streak_count + 0.5));  // glare_ray_cells
    const double half_width_rad = 0.1 * 2.0 * M_PI / n;
    rays_.set("u_reach", static_cast<float>(1.01 * std::tan(g.extent_rad) / std::cos(half_width_rad)));
    rays_.set("u_tangents", frame_->view.tangents());
    rays_.set("u_size", frame_->view.size());
    rays_.set("u_projection", glm::mat4(frame_->view.frustum->projection(SphereView::kNear, SphereView::kFar)));
    glDrawArrays(GL_TRIANGLES, 0, 3 * static_cast<int>(n));
}

}  // namespace cupola

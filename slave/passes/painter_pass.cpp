#include "passes/painter_pass.hpp"

#include <stdexcept>

#include "passes/atmosphere_pass.hpp"

namespace cupola {

PainterPass::PainterPass(const SceneConfig& scene, const ClusterConfig& cluster, const EclipseShadowUniforms& shadows)
    : shadows_(shadows), bodies_(scene), terrain_(scene, cluster) {}

void PainterPass::draw_terrain(const FrameBody& body) {
    const GlTexture* map = bodies_.texture(body.body->id);
    if (!map) return;
    const GpuAtmosphere* air = nullptr;
    if (atmosphere_) {
        const auto a = atmosphere_->atmospheres().find(body.body->id);
        if (a != atmosphere_->atmospheres().end()) air = a->second.get();
    }
    terrain_.draw(*frame_, body, *map, air);
}

int PainterPass::prepare_at(const FrameContext& frame, bool after_sky) {
    if (after_sky && !atmosphere_)
        throw std::logic_error(
            "sun and bodies: drawn after the sky without an atmosphere to take the air in front from");
    frame_ = &frame;
    after_sky_ = after_sky;
    return 1;
}

void PainterPass::draw(const PassInputs&, int) {
    const FrameContext& f = *frame_;
    const SkyInFrontSource* sky = after_sky_ ? atmosphere_ : nullptr;
    for (const FrameBody& it : f.far_to_near) {
        if (it.body->kind == BodyKind::Star)
            sun_.draw(f.view, *it.body, it.sphere, sky, it.light.disc_weight, it.light.small_disc);
        else if (draws_terrain(f, it))
            draw_terrain(it);
        else if (!atmosphere_ || !atmosphere_->draws_surface(f, it)) {
            bodies_.draw(f.view, *it.body, *it.state, it.sphere, f.light, shadows_, f.casters_of(it.body->id), sky,
                         it.light);
            bodies_.draw_rings(f.view, it, f.light, sky);
        }
    }
}

}  // namespace cupola

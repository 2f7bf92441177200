#include "passes/painter_pass.hpp"

#include "passes/atmosphere_pass.hpp"

namespace cupola {

PainterPass::PainterPass(const SceneConfig& scene, const EclipseShadowUniforms& shadows)
    : shadows_(shadows), bodies_(scene) {}

int PainterPass::prepare(const FrameContext& frame) {
    frame_ = &frame;
    return 1;
}

void PainterPass::draw(const PassInputs&, int) {
    const FrameContext& f = *frame_;
    for (const FrameBody& it : f.far_to_near) {
        if (it.body->kind == BodyKind::Star)
            sun_.draw(f.view, *it.body, it.sphere);
        else if (!atmosphere_ || !atmosphere_->draws_surface(f, it))
            bodies_.draw(f.view, *it.body, *it.state, it.sphere, f.light, shadows_, f.casters_of(it.body->id));
    }
}

}  // namespace cupola

#include "passes/eclipse_shadow_uniforms.hpp"

#include <string>

#include "eclipse/eclipse_reference.hpp"

namespace cupola {

namespace {
double scene_sun_limb_u(const SceneConfig& scene) {
    for (const auto& b : scene.bodies)
        if (b.kind == BodyKind::Star) return b.limb_darkening_u;
    return 0.0;
}

GlTexture make_lut(double limb_u) {
    const shading::Texture2DData t =
        eclipse::build_eclipse_lut(limb_u, eclipse::kEclipseLutWidth, eclipse::kEclipseLutHeight);
    return GlTexture(t.width, t.height, t.texels.data(), GL_LINEAR);
}
}  // namespace

EclipseShadowUniforms::EclipseShadowUniforms(double limb_u)
    : lut_(make_lut(limb_u)), lut_size_(eclipse::kEclipseLutWidth, eclipse::kEclipseLutHeight) {}

EclipseShadowUniforms::EclipseShadowUniforms(const SceneConfig& scene)
    : EclipseShadowUniforms(scene_sun_limb_u(scene)) {}

void EclipseShadowUniforms::apply(const GlProgram& p, const shading::EclipseCasters& e, GLuint unit) const {
    p.set("u_ecl.count", e.count);
    p.set("u_ecl.mode", e.mode);
    p.set("u_ecl.limb_u", e.limb_u);
    p.set("u_ecl.butterworth_order", e.butterworth_order);
    p.set("u_ecl.sun_position_m", e.sun_position_m);
    p.set("u_ecl.sun_radius_m", e.sun_radius_m);
    for (int i = 0; i < e.count; ++i) {
        const std::string k = "[" + std::to_string(i) + "]";
        p.set(("u_ecl.caster_position_m" + k).c_str(), e.caster_position_m[i]);
        p.set(("u_ecl.caster_radius_m" + k).c_str(), e.caster_radius_m[i]);
        p.set(("u_ecl.umbra_light" + k).c_str(), e.umbra_light[i]);
    }
    p.set("u_eclipse_lut", static_cast<int>(unit));
    p.set("u_eclipse_lut_size", lut_size_);
    lut_.bind(unit);
}

}  // namespace cupola

#include "passes/moonlight.hpp"

namespace cupola {

SkySecondLight brightest_moonlight(const FrameContext& f) {
    SkySecondLight out;
    const FrameBody* best = nullptr;
    for (const FrameBody& b : f.far_to_near)
        if (b.body->kind != BodyKind::Star && b.light.flux > 0.0 && (!best || b.light.flux > best->light.flux))
            best = &b;
    if (!best) return out;
    const auto casters = f.casters.find(best->body->id);
    out.present = true;
    out.position_m = best->state->position_m;
    out.irradiance_rgb = best->light.flux * best->light.unit_color *
                         (casters == f.casters.end() ? glm::dvec3(1.0) : sunlight_at_centre(casters->second));
    return out;
}

}  // namespace cupola

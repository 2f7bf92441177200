#include "eclipse/umbra_light.hpp"

#include "shading/shared_shading.hpp"

namespace cupola {

glm::vec3 grazing_transmittance(const atmosphere::ProductionAtmosphere& model, double altitude_m) {
    const shading::AtmosphereParams& a = model.shader_params();
    const shading::Texture2DData& t = model.tables().transmittance;
    const float r = a.bottom_radius_m + static_cast<float>(altitude_m);
    const glm::vec3 half =
        shading::atm_lookup_transmittance(a, shading::sampler2D{&t}, glm::vec2(t.width, t.height), r, 0.0f);
    return half * half;
}

glm::vec3 umbra_light(const BodyConfig& body, const atmosphere::ProductionAtmosphere* model) {
    if (body.umbra_light) return *body.umbra_light;
    if (!model) return glm::vec3(0.0f);
    return grazing_transmittance(*model, kUmbraRayAltitude_m) * static_cast<float>(body.umbra_brightness);
}

}  // namespace cupola

#include "atmosphere/moonlit_sky.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/sky_view_table.hpp"

namespace cupola {

glm::dvec3 sunlight_at_centre(const shading::EclipseCasters& casters) {
    if (casters.count == 0 || casters.mode == shading::ECLIPSE_MODE_ILLUSTRATIVE) return glm::dvec3(1.0);
    shading::EclipseCasters c = casters;
    c.mode = shading::ECLIPSE_MODE_EXACT;
    return glm::dvec3(shading::eclipse_light(c, shading::sampler2D{}, glm::vec2(1.0f), glm::vec3(0.0f)));
}

double sky_luminance(const atmosphere::ProductionAtmosphere& model, double d_m, const glm::dvec3& view,
                     const glm::dvec3& source, glm::dvec3* transmittance) {
    const shading::AtmosphereParams& a = model.shader_params();
    const double d =
        std::clamp(d_m, static_cast<double>(a.bottom_radius_m) + 1.0, static_cast<double>(a.top_radius_m) - 1.0);
    const shading::AtmosphereRayStart st = shading::atm_ray_start(a, static_cast<float>(d), glm::vec3(view),
                                                                  glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(source));
    glm::vec3 t;
    const double y = model.to_xyz(model.radiance(st, -1.0f, &t)).y;
    if (transmittance) *transmittance = glm::dvec3(t);
    return y;
}

double zenith_sky_luminance(const atmosphere::ProductionAtmosphere& model, double d_m, double mu) {
    const double m = std::clamp(mu, -1.0, 1.0);
    return sky_luminance(model, d_m, glm::dvec3(0.0, 0.0, 1.0), glm::dvec3(std::sqrt(1.0 - m * m), 0.0, m));
}

MoonOnAir moon_on_air(const SkySecondLight& moon, const glm::dvec3& camera_m, const glm::dvec3& planet_m,
                      const glm::dvec3& sun_dir_world, double sun_irradiance,
                      const atmosphere::ProductionAtmosphere& model) {
    MoonOnAir out;
    const glm::dvec3 up_m = camera_m - planet_m;
    const double d = glm::length(up_m);
    if (!moon.present || !(sun_irradiance > 0.0) || !(d > 0.0) || d >= model.shader_params().top_radius_m) return out;
    const glm::dvec3 to_moon = moon.position_m - camera_m;
    if (!(glm::length(to_moon) > 0.0)) return out;
    out.dir_world = glm::normalize(to_moon);
    out.ratio_rgb = moon.irradiance_rgb / sun_irradiance;
    const glm::dvec3 up = up_m / d;
    out.mu = atmosphere::sky_view_table_sun_mu(glm::dot(up, out.dir_world));
    const double ratio = shading::rec709_luminance(glm::vec3(out.ratio_rgb));
    const double moon_sky = ratio * zenith_sky_luminance(model, d, out.mu);
    const double sun_sky =
        zenith_sky_luminance(model, d, atmosphere::sky_view_table_sun_mu(glm::dot(up, sun_dir_world)));
    out.on = moon_sky > 0.0 && moon_sky >= kMoonlitSkyMinShare * sun_sky;
    return out;
}

}  // namespace cupola

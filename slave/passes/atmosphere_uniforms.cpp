#include "passes/atmosphere_uniforms.hpp"

#include "atmosphere/solar_scale.hpp"
#include "passes/atmosphere_pass.hpp"
#include "passes/body_pass.hpp"

namespace cupola {

namespace {
glm::vec2 size_of(const shading::Texture2DData& t) { return glm::vec2(t.width, t.height); }
}  // namespace

void set_atmosphere_params(const GlProgram& p, const shading::AtmosphereParams& a, const std::string& name) {
    p.set((name + ".bottom_radius_m").c_str(), a.bottom_radius_m);
    p.set((name + ".top_radius_m").c_str(), a.top_radius_m);
    p.set((name + ".rayleigh_scattering_per_m").c_str(), a.rayleigh_scattering_per_m);
    p.set((name + ".rayleigh_scale_height_m").c_str(), a.rayleigh_scale_height_m);
    p.set((name + ".mie_scattering_per_m").c_str(), a.mie_scattering_per_m);
    p.set((name + ".mie_extinction_per_m").c_str(), a.mie_extinction_per_m);
    p.set((name + ".mie_scale_height_m").c_str(), a.mie_scale_height_m);
    p.set((name + ".mie_g").c_str(), a.mie_g);
    p.set((name + ".ozone_absorption_per_m").c_str(), a.ozone_absorption_per_m);
    p.set((name + ".ozone_bottom_m").c_str(), a.ozone_bottom_m);
    p.set((name + ".ozone_peak_m").c_str(), a.ozone_peak_m);
    p.set((name + ".ozone_top_m").c_str(), a.ozone_top_m);
    p.set((name + ".ground_albedo").c_str(), a.ground_albedo);
}

void bind_atmosphere_tables(const GlProgram& p, const GpuAtmosphere& atm, GLuint first_unit) {
    const atmosphere::ProductionAtmosphere& m = atm.model();
    p.set("u_trans_size", size_of(m.tables().transmittance));
    p.set("u_ms_size", size_of(m.tables().multiple_scattering));
    p.set("u_irr_size", size_of(m.tables().irradiance));
    p.set("u_weight_count", static_cast<float>(m.color_weights().width));
    p.set("u_transmittance", static_cast<int>(first_unit));
    p.set("u_multiple_scattering", static_cast<int>(first_unit + 1));
    p.set("u_irradiance", static_cast<int>(first_unit + 2));
    p.set("u_weights", static_cast<int>(first_unit + 3));
    atm.bind(first_unit);
}

PlanetSun planet_sun(const BodyState& state, const SunLight& sun, const atmosphere::ProductionAtmosphere* m) {
    PlanetSun out;
    if (!sun.present) return out;
    const glm::dvec3 to_sun = sun.position_m - state.position_m;
    const double d_sun = glm::length(to_sun);
    if (d_sun <= 0.0) return out;
    out.dir_world = to_sun / d_sun;
    out.irradiance = sun_irradiance(sun, d_sun);
    if (m) out.solar_scale = out.irradiance / atmosphere::physical_solar_illuminance(*m);
    return out;
}

}  // namespace cupola

#pragma once
// The uniforms every atmosphere shader shares: the AtmosphereParams struct (u_atm) and the
// production tables with their sizes (u_transmittance, u_multiple_scattering, u_irradiance,
// u_weights and u_*_size, u_weight_count).
#include "atmosphere/production_model.hpp"
#include <string>

#include "gl/gl_program.hpp"
#include "passes/frame_context.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

class GpuAtmosphere;

// The Sun seen from a planet's centre: its direction (world), its irradiance there (scene units)
// and, for the planet's air, the scale from the production tables' units (per unit of the model's
// physical solar illuminance) to scene units. All 0 (the direction +z) without a Sun.
struct PlanetSun {
    glm::dvec3 dir_world{0.0, 0.0, 1.0};
    double solar_scale = 0.0;  // 0: no Sun, or no air given
    double irradiance = 0.0;   // scene units
};
// m: the planet's atmosphere model, or null (no solar scale).
PlanetSun planet_sun(const BodyState& state, const SunLight& sun, const atmosphere::ProductionAtmosphere* m);

// `name`: the uniform struct's name in the shader.
void set_atmosphere_params(const GlProgram& program, const shading::AtmosphereParams& a,
                           const std::string& name = "u_atm");
// Binds the model's tables to units first_unit .. first_unit + 3 and sets the samplers and sizes.
void bind_atmosphere_tables(const GlProgram& program, const GpuAtmosphere& atmosphere, GLuint first_unit);

}  // namespace cupola

#pragma once
// The uniforms every atmosphere shader shares: the AtmosphereParams struct (u_atm) and the
// production tables with their sizes (u_transmittance, u_multiple_scattering, u_irradiance,
// u_weights and u_*_size, u_weight_count).
#include "atmosphere/production_model.hpp"
#include <string>

#include "gl/gl_program.hpp"

namespace cupola {

class GpuAtmosphere;

// `name`: the uniform struct's name in the shader.
void set_atmosphere_params(const GlProgram& program, const shading::AtmosphereParams& a,
                           const std::string& name = "u_atm");
// Binds the model's tables to units first_unit .. first_unit + 3 and sets the samplers and sizes.
void bind_atmosphere_tables(const GlProgram& program, const GpuAtmosphere& atmosphere, GLuint first_unit);

}  // namespace cupola

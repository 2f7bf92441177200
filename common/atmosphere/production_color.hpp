#pragma once
// The colour side of the production atmosphere: the table of per-wavelength XYZ weights that
// atm_samples_to_xyz() (shaders/shared/atmosphere_color.glsl) integrates over. Photometric:
// Y is the luminance in cd m^-2 for a radiance given per unit solar irradiance.
#include <glm/glm.hpp>

#include "atmosphere/atmosphere_parameters.hpp"
#include "shading/shared_shading.hpp"

namespace cupola::atmosphere {

inline constexpr int kColorWavelengths = 48;  // 360..830 nm in 10 nm steps

shading::Texture2DData production_color_weights(const AtmosphereParameters& p);

}  // namespace cupola::atmosphere

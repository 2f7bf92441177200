#include "atmosphere/production_color.hpp"

#include "atmosphere/spectral_color.hpp"

namespace cupola::atmosphere {

shading::Texture2DData production_color_weights(const AtmosphereParameters& p) {
    shading::Texture2DData t;
    t.width = kColorWavelengths;
    t.height = 1;
    for (int k = 0; k < kColorWavelengths; ++k) {
        const double l = 360.0 + 10.0 * k;
        const double dl = (k == 0 || k == kColorWavelengths - 1) ? 5.0 : 10.0;  // trapezoid ends
        const glm::dvec3 w = kLuminousEfficacy * dl * p.solar_irradiance(l) * cie1931_xyz_bar(l);
        t.texels.emplace_back(glm::vec3(w), static_cast<float>(l));
    }
    return t;
}

}  // namespace cupola::atmosphere

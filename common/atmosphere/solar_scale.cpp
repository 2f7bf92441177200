#include "atmosphere/solar_scale.hpp"

#include <cmath>

namespace cupola::atmosphere {

double sun_irradiance_scene_units(const BodyConfig& sun, double distance_m) {
    const double s = sun.radius_m / std::max(distance_m, sun.radius_m);
    return sun.radiance * M_PI * s * s * (1.0 - sun.limb_darkening_u / 3.0);
}

double physical_solar_illuminance(const ProductionAtmosphere& model) {
    double y = 0.0;
    for (const auto& w : model.color_weights().texels) y += w.y;
    return y;
}

double solar_scale(const ProductionAtmosphere& model, const BodyConfig& sun, double distance_m) {
    return sun_irradiance_scene_units(sun, distance_m) / physical_solar_illuminance(model);
}

}  // namespace cupola::atmosphere

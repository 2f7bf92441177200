#include "atmosphere/solar_scale.hpp"

#include <cmath>

namespace cupola::atmosphere {

double sun_irradiance_scene_units(double radiance, double radius_m, double limb_u, double distance_m) {
    const double s = radius_m / std::max(distance_m, radius_m);
    return radiance * M_PI * s * s * (1.0 - limb_u / 3.0);
}

double sun_irradiance_scene_units(const BodyConfig& sun, double distance_m) {
    return sun_irradiance_scene_units(sun.radiance, sun.radius_m, sun.limb_darkening_u, distance_m);
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

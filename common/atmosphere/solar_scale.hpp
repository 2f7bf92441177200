#pragma once
// Scene units for the atmosphere. The production model's radiance is photometric (cd m^-2) for the
// physical solar spectrum; a scene's Sun has its own disc radiance in scene units. The factor
// below makes sky and Sun agree: sky in scene units = sky in cd m^-2 * solar_scale.
#include "atmosphere/production_model.hpp"
#include "config/scene_config.hpp"

namespace cupola::atmosphere {

// The physical Sun's disc-centre luminance (cd/m^2): a scene's Sun radiance stands for it, so a
// scene radiance times kPhysicalSunRadiance_cd_m2 / the Sun's radiance is a luminance.
inline constexpr double kPhysicalSunRadiance_cd_m2 = 2.0e9;

// Irradiance (scene units) of a limb-darkened Sun disc of disc-centre radiance L, radius R and
// linear limb-darkening u seen from distance_m: L * pi * (R / d)^2 * (1 - u / 3), with R / d
// capped at 1. The one formula the body pass, the atmosphere pass and the auto exposure use.
double sun_irradiance_scene_units(double radiance, double radius_m, double limb_u, double distance_m);
double sun_irradiance_scene_units(const BodyConfig& sun, double distance_m);

// Illuminance (lux) of the model's physical Sun: Y of f = 1 in every channel.
double physical_solar_illuminance(const ProductionAtmosphere& model);

// sun_irradiance_scene_units / physical_solar_illuminance.
double solar_scale(const ProductionAtmosphere& model, const BodyConfig& sun, double distance_m);

// The factor that turns the model's sky (per unit solar irradiance, as the tables hold it) into
// cd/m^2 for a scene whose Sun has disc radiance sun_radiance: the sky in scene units
// (solar_scale) read against the physical Sun (kPhysicalSunRadiance_cd_m2).
inline double sky_to_cd_m2(double solar_scale, double sun_radiance) {
    return solar_scale * kPhysicalSunRadiance_cd_m2 / sun_radiance;
}

}  // namespace cupola::atmosphere

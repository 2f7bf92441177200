#pragma once
// The light a caster leaves deep in its umbra, per unit sunlight (Ekelin & Fernqvist 2009, section 5.1.7: the
// red Moon of a lunar eclipse). Sunlight grazing the caster's atmosphere is bent into the
// umbra; its colour is the transmittance of the grazing path (tangent altitude
// kUmbraRayAltitude_m, both halves: T(r, mu = 0)^2 at 680/550/440 nm taken as r/g/b), its
// level body.umbra_brightness (refraction's dilution, not modelled: a Danjon 2-3 eclipse
// leaves about 1e-4 of full sunlight). The scene's umbra_light, when given, wins; a caster with
// neither gives black.
#include <glm/glm.hpp>

#include "atmosphere/production_model.hpp"
#include "config/scene_config.hpp"

namespace cupola {

constexpr double kUmbraRayAltitude_m = 12000.0;  // above most clouds; refraction lifts lower rays less far

// Transmittance (680/550/440 nm) of the straight path grazing the atmosphere at the altitude.
glm::vec3 grazing_transmittance(const atmosphere::ProductionAtmosphere& model, double altitude_m);

// `model` may be null (a body without an atmosphere).
glm::vec3 umbra_light(const BodyConfig& body, const atmosphere::ProductionAtmosphere* model);

}  // namespace cupola

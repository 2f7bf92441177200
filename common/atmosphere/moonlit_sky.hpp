#pragma once
// The moonlit sky: a planet's air lit by a second source, the brightest planet or moon at the
// camera (the Moon, seen from the Earth), through the same tables as the Sun's light. The air's
// response to a distant source depends only on the source's direction, so the Moon's sky is the
// sky-view table rendered for the Moon's zenith angle (a second table) times the Moon's
// irradiance over the Sun's, in the Moon's colour. Whether the Moon's light is drawn at all is
// decided once per frame, from the snapshot in double, by how much it adds to the sky at the
// zenith: the slaves (slave/passes/moonlight.hpp: the light) and the master's exposure alike.
#include <glm/glm.hpp>

#include "atmosphere/production_model.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

// A second light: its position (world, double) and its irradiance at the camera (scene units,
// linear RGB); present false: none.
struct SkySecondLight {
    bool present = false;
    glm::dvec3 position_m{0.0};
    glm::dvec3 irradiance_rgb{0.0};
};

// The Moon's light on one planet's air, for a camera inside it.
struct MoonOnAir {
    bool on = false;
    glm::dvec3 dir_world{0.0, 0.0, 1.0};  // unit, camera -> the Moon (as the camera sees it)
    glm::dvec3 ratio_rgb{0.0};            // its irradiance over the Sun's at the planet
    float mu = 0.0f;                      // its zenith cosine at the camera, on the tables' grid
};

// The Moon's light is drawn when it adds at least this share of the sky's luminance at the zenith
// (the Sun's sky there, from the same model): from the end of civil twilight on with a Moon well
// up, never by day (a full Moon's sky is about 4e-6 of the sky with the Sun 10 degrees up).
constexpr double kMoonlitSkyMinShare = 1e-3;

// camera_m, planet_m: world positions; sun_dir_world: unit, planet centre -> Sun;
// sun_irradiance: the Sun's at the planet, in the units of moon.irradiance_rgb. Off outside the
// air (from space the Moon's light on the night side is left out) and without a Moon.
MoonOnAir moon_on_air(const SkySecondLight& moon, const glm::dvec3& camera_m, const glm::dvec3& planet_m,
                      const glm::dvec3& sun_dir_world, double sun_irradiance,
                      const atmosphere::ProductionAtmosphere& model);

// The model's sky luminance (cd/m^2 per unit solar irradiance of the physical spectrum) along
// `view` for a distant source along `source`, both unit vectors in the camera's local frame (z up),
// for a camera d_m from the centre (clamped into the air). transmittance: the view ray's, at the
// model's sample wavelengths, if wanted.
double sky_luminance(const atmosphere::ProductionAtmosphere& model, double d_m, const glm::dvec3& view,
                     const glm::dvec3& source, glm::dvec3* transmittance = nullptr);
// The same at the zenith for a source at zenith cosine mu.
double zenith_sky_luminance(const atmosphere::ProductionAtmosphere& model, double d_m, double mu);

// The sunlight left at a receiver's centre by its eclipse casters (1 without any). A numeric mode
// is evaluated exactly at the one point; the illustrative mode's tints are display colours, not
// light, and leave the light whole.
glm::dvec3 sunlight_at_centre(const shading::EclipseCasters& casters);

}  // namespace cupola

#pragma once
// The scene: which bodies exist, their sizes, looks and ephemeris model, and the star field.
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "atmosphere/atmosphere_parameters.hpp"

namespace cupola {

enum class BodyKind { Star, Planet, Moon };

// A body's atmosphere: a physical preset ("earth", "mars") with optional overrides, resolved to
// full parameters whose ground is the body's radius; and the production model's quality level.
struct AtmosphereConfig {
    bool present = false;
    std::string preset;
    std::string model = "medium";  // atmosphere::production_quality() name
    atmosphere::AtmosphereParameters parameters;
};

struct BodyConfig {
    uint16_t id = 0;            // index in SceneConfig::bodies; the snapshot refers to bodies by it
    std::string name;
    BodyKind kind = BodyKind::Planet;
    std::string ephemeris;      // analytic model: "sun", "earth" or "moon"
    double radius_m = 1.0;
    std::string texture;        // resolved image path, or "generated:<name>"
    glm::vec3 tint{1.0f};       // multiplies the texture (or the disc colour of a star)
    double albedo = 0.3;        // planets and moons
    double limb_darkening_u = 0.6;  // stars: linear limb-darkening coefficient
    double radiance = 1.0e3;    // stars: disc-centre radiance in scene units (planets are lit by it)
    AtmosphereConfig atmosphere;  // planets and moons
};

struct StarFieldConfig {
    std::string catalog;              // resolved path of the compact star catalogue (CSV)
    double magnitude_limit = 6.5;
    double psf_sigma_arcmin = 2.0;    // angular size of a star, cluster-wide
    double zero_mag_flux = 2.0e-3;    // integrated flux of a V=0 star in scene units x steradian
};

struct SceneConfig {
    std::string file;
    std::vector<BodyConfig> bodies;
    StarFieldConfig stars;

    const BodyConfig* find(const std::string& name) const;
};

SceneConfig load_scene_config(const std::string& file);

}  // namespace cupola

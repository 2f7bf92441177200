#pragma once
// The scene: which bodies exist, their sizes, looks and ephemeris model, and the star field.
// The file format, each field's default, range and meaning: configs/schema/scene.schema.json
// (docs/CONFIG.md is written from it). The initialisers below are those defaults, for code that
// builds a scene without a file; test_config_schema checks they match the schema.
#include <glm/glm.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_parameters.hpp"
#include "overlay/overlay_kind.hpp"
#include "shading/shared_types.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

enum class BodyKind { Star, Planet, Moon };
// How a planet's or moon's surface reflects (shaders/shared/surface_photometry.glsl).
enum class Photometry { Lambert, LunarLambert };

// A body's atmosphere: a physical preset ("earth", "mars") with optional overrides, resolved to
// full parameters whose ground is the body's radius; and the production model's quality level.
struct AtmosphereConfig {
    bool present = false;
    std::string preset;
    std::string model = "sky-view";  // atmosphere::production_quality() name
    atmosphere::AtmosphereParameters parameters;
};

// A planet's rings: a thin slab in its equatorial plane (shaders/shared/ring_photometry.glsl), whose
// normal optical depth follows a radial map: tau = optical_depth x (the map's linear value)^2.
struct RingConfig {
    bool present = false;
    std::string texture;  // resolved image path; its columns run from the inner radius to the outer
    double inner_radius_m = 0.0, outer_radius_m = 0.0;  // what the map's first and last columns span
    double optical_depth = 4.0;                         // tau where the map reads 1
    double phase_albedo = 1.0;                          // varpi0 P where the map reads 1 (it scales with the map)
    glm::vec3 tint{1.0f};
};

// A body's relief, drawn as a quadtree of tiles (common/terrain/) instead of a smooth sphere: heights
// from an elevation file where it has data, band-limited procedural relief above its resolution and
// where it has none. The detail is chosen once for the whole cluster against error_budget_px.
struct TerrainConfig {
    bool present = false;
    double error_budget_px = 1.0;            // the largest screen-space error of the cut, in the dome's finest pixels
    int segments = 32;                       // quads along a tile's side
    std::string elevation;                   // resolved GDAL-readable file, or empty: procedural relief alone
    double procedural_wavelength_m = 200e3;  // the longest octave
    double procedural_amplitude_m = 1500.0;  // its amplitude
    double procedural_gain = 0.5;            // amplitude ratio between octaves
    int procedural_octaves = 20;
    uint64_t seed = 1;
    size_t cache_tiles = 3000;  // tile meshes kept in memory
    int workers = 2;            // tile-building threads
};

struct BodyConfig {
    uint16_t id = 0;  // index in SceneConfig::bodies; the snapshot refers to bodies by it
    std::string name;
    BodyKind kind = BodyKind::Planet;
    std::string ephemeris;    // analytic model: "sun", "earth", "moon", "mercury" ... "neptune", "pluto", "io" ...
                              // "callisto", "titan"
    double radius_m = 1.0;    // equatorial radius (the mean one for a sphere)
    double flattening = 0.0;  // (a - c) / a: the polar radius is radius_m * (1 - flattening)
    std::string texture;      // resolved image path, or "generated:<name>"
    glm::vec3 tint{1.0f};     // multiplies the texture (or the disc colour of a star)
    double albedo = 0.3;      // planets and moons
    Photometry photometry = Photometry::Lambert;
    double limb_darkening_u = 0.6;  // stars: linear limb-darkening coefficient
    double radiance = 1.0e3;        // stars: disc-centre radiance in scene units (planets are lit by it)
    AtmosphereConfig atmosphere;    // planets and moons
    // As an eclipse caster: the light left deep in its umbra, per unit sunlight (rgb). A body
    // with an atmosphere derives it from the atmosphere's grazing transmittance times
    // umbra_brightness unless umbra_light is given; without one, umbra_light (default black).
    std::optional<glm::vec3> umbra_light;
    double umbra_brightness = 2.5e-4;
    double corona = 1.0;    // stars: corona brightness relative to Baumbach's mean K+F corona (0: none)
    RingConfig rings;       // planets
    TerrainConfig terrain;  // planets and moons
};

// Which bodies shadow which (Ekelin & Fernqvist 2009, section 3.3.3): in a group the parent shadows its
// children and each child shadows the parent; children shadow each other only if the group
// says so.
struct ShadowGroupConfig {
    uint16_t parent = 0;
    std::vector<uint16_t> children;
    bool siblings_shadow_each_other = false;
};

// The numbers are the shaders' ECLIPSE_MODE_* (shaders/shared/eclipse_types.glsl), defined there only.
enum class ShadowMode : uint32_t {
    Exact = shading::ECLIPSE_MODE_EXACT,
    Fast = shading::ECLIPSE_MODE_FAST,
    Lookup = shading::ECLIPSE_MODE_LUT,
    Illustrative = shading::ECLIPSE_MODE_ILLUSTRATIVE,
    Off = shading::ECLIPSE_MODE_OFF
};
const std::vector<std::string>& shadow_mode_names();        // "exact", "fast", "lut", "illustrative", "off"
ShadowMode shadow_mode_from_name(const std::string& name);  // throws std::invalid_argument

struct ShadowConfig {
    ShadowMode mode = ShadowMode::Exact;  // default; a show keyframe may switch it
    double butterworth_order = 4.0;       // fast mode's umbra edge
    std::vector<ShadowGroupConfig> groups;
};

struct StarFieldConfig {
    std::string catalog;  // resolved path of the compact star catalogue (CSV)
    double magnitude_limit = 6.5;
    double psf_sigma_arcmin = 2.0;           // angular size of a star, cluster-wide
    double zero_mag_flux = 2.0e-3;           // integrated flux of a V=0 star in scene units x steradian
    TwinkleMode twinkle = TwinkleMode::Off;  // until a show or the presenter changes it
    // The night sky's own zenith brightness, V mag/arcsec^2 (stars.sky_brightness, or a Bortle
    // class's: common/scene/night_sky.hpp); none: only the light the atmosphere scatters.
    std::optional<double> sky_brightness_mag_arcsec2;
};

// How a channel decides how much of a glare source is visible: from the whole cluster's
// measurements, shared by the master (seamless), or from its own query only and only while the
// source's centre is in its own frustum -- the naive behaviour that clips the glare at channel
// edges (Ekelin & Fernqvist 2009, section 5.1.1), kept as a switch so tests can show the difference.
enum class GlareVisibilityMode { Shared, PerChannel };

// Sun glare (Ekelin & Fernqvist 2009, sections 2.3 and 3.1; Spencer et al. 1995): bloom, lenticular halo and
// ciliary-corona streaks on a viewpoint-oriented billboard per bright source, drawn last. Absent
// from the scene file: no glare.
struct GlareConfig {
    bool enabled = false;
    double strength = 1.0;         // x the physical point-spread function of the eye
    double extent_deg = 60.0;      // nothing beyond this angle from a source
    double halo_radius_deg = 3.5;  // lenticular halo ring at 550 nm (design value)
    double halo_width_deg = 0.35;
    double halo_fraction = 0.15;  // share of the flare energy in the ring
    int streak_count = 96;        // ciliary-corona rays
    double streak_contrast = 0.6;
    double animation_rate = 1.0;  // animation phase per show second (carried in the snapshot)
    GlareVisibilityMode visibility = GlareVisibilityMode::Shared;
    // Stars and planets get a glare when its display value one degree from them (irradiance x
    // exposure x PSF) reaches min_display; it fades in up to twice that, so nothing pops.
    double min_display = 2e-3;
    int max_sources = 8;      // the brightest sources, the Sun first
    int probe_size = 64;      // occlusion-query probe, pixels per side
    int halo_downsample = 4;  // the halo at 1/this resolution per axis (1: all at full resolution)
};

// The Milky Way as a map in galactic coordinates (passes/milky_way_pass).
struct MilkyWayConfig {
    bool present = false;
    std::string texture;               // resolved image path
    double surface_brightness = 20.5;  // V mag / arcsec^2 of the map's brightest 1 % of texels
    double latitude_extent_deg = 0.0;  // of the top row; 0: from the map's shape (square texels)
};

// One overlay's look (configs/schema/scene.schema.json, definitions.overlay_style).
struct OverlayStyle {
    bool visible = false;
    glm::dvec3 color{0.6, 0.6, 0.6};  // display colour, linear 0..1
    double width_deg = 0.1;           // line width, dome degrees
    double text_deg = 1.6;            // text em height, dome degrees
    double fade_s = 1.0;
};

// The presenter's overlays (common/overlay/overlay_kind.hpp). Absent from the scene: none.
// The look an overlay has when the scene gives none: planetarium colours (blue figures, the
// grids in the colours of their frames), lines 0.1 degrees wide (grids 0.06), text 1.6 degrees.
OverlayStyle default_overlay_style(OverlayKind kind);

struct OverlaysConfig {
    bool present = false;
    std::string figures;  // resolved path of the constellation data
    std::array<OverlayStyle, kOverlayCount> styles;
};

struct SceneConfig {
    std::string file;
    std::vector<BodyConfig> bodies;
    StarFieldConfig stars;
    ShadowConfig shadows;
    GlareConfig glare;
    MilkyWayConfig milky_way;
    OverlaysConfig overlays;

    const BodyConfig* find(const std::string& name) const;
};

SceneConfig load_scene_config(const std::string& file);

}  // namespace cupola

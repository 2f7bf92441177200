#pragma once
// How much light a planet or moon sends to the camera, and whether it is drawn as a point, as a
// disc, or as both fading into each other. Decided once per frame from the snapshot and from
// cluster-wide constants (the star PSF's angle, the cluster's coarsest pixel), so every channel
// draws a body alike.
//
// The surface: Lambertian, or lunar-Lambert (BodyConfig::photometry; the Moon), whose phase
// function is the measured curve over the model's disc integral.
// The light: for a planet with a measured phase curve (scene/planet_magnitude, Mallama & Hilton
// 2018) its V magnitude (for Saturn with its rings drawn, the globe's and the rings' together; its
// disc the globe's alone, the rings drawing their own), as a flux in scene units: the Sun's irradiance at 1 AU times
// 10^(-0.4 (V - V_sun)). Otherwise what the drawn disc gives: a Lambert sphere of albedo times its
// map's mean, F_L = 2/3 A E (R / Delta)^2 Phi_L(alpha), times the projected area of an oblate
// spheroid over pi a^2, times how the map's lit and visible part compares with its mean
// (lit_map_ratio, summed on a 64 x 32 grid of the map each frame). The disc's radiance is scaled by disc_scale = F /
// F_L, so that disc and point carry the same energy (what the issue calls equal energy at the handover).
//
// Point or disc: a body whose angular radius rho is below handover_start draws as a point (the
// stars' PSF, sigma widened to sqrt(sigma^2 + rho^2 / 4), a uniform disc's second moment); above
// twice that, as its disc; in between both, the disc with weight w = smoothstep and the point with
// 1 - w. handover_start = max(2 sigma, 4 coarsest pixels): the disc, edge-antialiased in body.frag
// and read from its map's mip level, is then at least four pixels in radius on every channel when
// it begins to show, where its drawn light is within about 1 % of its integral. The disc is always
// drawn, with its light times w: as a point it still hides what is behind it (a transit, an
// eclipse).
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

#include "config/scene_config.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// A disc under 4 x handover_start drawn by a shader that cannot antialias it analytically (a
// planet's air: atmosphere_lookup.frag; rings: ring.frag) takes n x n rays a pixel
// (PlanetLight::supersample): at 8 to 16 pixels in radius one ray a pixel left the Earth's light
// 3 to 6 % off from frame to frame.
constexpr int kSmallDiscSupersample = 4;

struct PlanetLight {
    double flux = 0.0;         // scene units x sr at the camera: the whole body
    double disc_scale = 1.0;   // multiplies the Lambert disc's radiance (body.frag u_lit)
    double disc_weight = 1.0;  // 0: a point only; 1: the disc only
    double point_sigma_rad = 0.0;
    glm::dvec3 unit_color{1.0};  // the map's mean colour at unit luminance
    // Small enough on every channel (below 8 x handover_start) for body.frag to antialias its limb
    // and shade a limb pixel inside it; a large disc keeps the exact per-pixel hit.
    bool small_disc = false;
    // Rays a pixel along each axis for the air's and the rings' draws: kSmallDiscSupersample below
    // 4 x handover_start, else 1.
    int supersample = 1;
    // The surface's lunar-Lambert weight L at this phase (0: Lambert; shared/surface_photometry.glsl).
    double limb_weight = 0.0;
    // Light from the body a moon circles (earthshine): its irradiance here times albedo / pi, the
    // phase function at the shine's own phase angle and the source's colour (body.frag u_shine_lit,
    // times the map); zero without one. Its direction (world, unit) and its L.
    glm::dvec3 shine_lit{0.0};
    glm::dvec3 shine_dir{0.0};
    double shine_limb_weight = 0.0;
    bool has_point() const { return disc_weight < 1.0 && flux > 0.0; }
    // What the point carries: (1 - disc weight) of the light, in the map's colour.
    glm::dvec3 point_color() const { return flux * (1.0 - disc_weight) * unit_color; }
};

// What a planet's light is computed from, besides the body itself.
// A body map reduced to kWidth x kHeight cells of mean linear luminance (row 0 = north), from which
// the lit, visible part's light is summed each frame: the disc's scale then matches its map where
// the Sun shines and the camera looks, not only the map's global mean.
struct LuminanceGrid {
    static constexpr int kWidth = 64, kHeight = 32;
    std::vector<float> cells;  // kWidth * kHeight; empty: a uniform map
};

// A body that lights another with the sunlight it reflects (the Earth on the Moon).
struct PlanetShine {
    glm::dvec3 position_m{0.0};
    double irradiance = 0.0;     // scene units, at the lit body
    glm::dvec3 unit_color{1.0};  // its light's colour at unit luminance
};

struct PlanetLightInputs {
    glm::dvec3 sun_position_m{0.0};
    double sun_irradiance_1au = 0.0;  // scene units; 0: no Sun (no light)
    glm::dvec3 camera_position_m{0.0};
    glm::dvec3 map_mean_rgb{1.0};             // linear, tint included, over the sphere's area
    const LuminanceGrid* map_grid = nullptr;  // its luminance by cell (tint included); null: uniform
    double psf_sigma_rad = 0.0;
    double handover_start_rad = 0.0;
    const PlanetShine* shine = nullptr;  // none: no planetshine
};

PlanetLight planet_light(const BodyConfig& body, const BodyState& state, const PlanetLightInputs& in);

// A planet with air (the Earth) as its air draws it: a resolved disc (weight 1) is the air's alone
// (the default light: no point, no scale); in the handover the air's draw (AtmospherePass) fades
// with the weight while the point carries the rest of air_flux_rgb (its light and colour), the air's own disc
// integrated for a distant observer (AtmospherePass::point_flux), so that point and disc carry the same energy. The air
// relights the surface itself, so the body pass's own colour (disc_scale 0) does not leak through the fading air.
PlanetLight with_air(const PlanetLight& light, const glm::dvec3& air_flux_rgb);
// The part of planet_light that with_air keeps: from disc to point (disc weight, point width,
// supersampling, small disc) by the body's angular size alone, without its light.
PlanetLight handover_light(const BodyConfig& body, const BodyState& state, const PlanetLightInputs& in);

// The irradiance at `lit_position_m` from `source` reflecting sunlight: its V magnitude from its
// phase curve seen from there when it has one (the Earth: Mallama & Hilton 2018), else a Lambert
// sphere of its albedo times its map's mean luminance. Both treat the source as a point: nearer
// than kPlanetshineMinRadii of its radii (its disc wider than 11 degrees; a boulder on the ground,
// or Io over Jupiter) that no longer holds, and this gives 0.
constexpr double kPlanetshineMinRadii = 10.0;
double planetshine_irradiance(const BodyConfig& source, const BodyState& source_state, double map_mean_luminance,
                              const glm::dvec3& lit_position_m, const glm::dvec3& sun_position_m,
                              double sun_irradiance_1au);

// A star of the scene (the Sun) from disc to point the same way: its flux is the irradiance its
// limb-darkened disc gives at the camera, in its tint; the disc (SunPass) is drawn times the
// weight. The map and Sun inputs are not used.
PlanetLight star_light(const BodyConfig& star, const BodyState& state, const PlanetLightInputs& in);

// A disc on the sky as the camera sees it: its centre's direction (unit) and angular radius.
struct SkyDisc {
    glm::dvec3 center_dir{0.0, 0.0, 1.0};
    double radius_rad = 0.0;
};

// The part of a star's limb-darkened disc (coefficient limb_u) that the nearer discs leave
// visible: each occluder's eclipse_visible_exact (shared/eclipse_shadow.glsl), multiplied. Exact for
// one occluder (the Moon before the Sun); two that overlap each other are counted twice. The
// star's point carries this part of its light, so a point-sized Sun behind the Moon neither leaks
// past the Moon's edge nor is hidden twice.
double star_visible_fraction(const SkyDisc& star, const std::vector<SkyDisc>& nearer, double limb_u);

// The grid of an image of width x height linear RGB (body_texture's BodyImage layout), times tint.
LuminanceGrid luminance_grid(int width, int height, const std::vector<float>& rgb, const glm::dvec3& tint);

// How the lit, visible part of the map compares with a uniform map of its mean: the sum over the
// grid of luminance x cos i x cos e, over the same sum with every cell at the mean (1 without a grid).
double lit_map_ratio(const LuminanceGrid* grid, double mean_luminance, const glm::dvec3& to_sun_body,
                     const glm::dvec3& to_camera_body, double limb_weight = 0.0);

// A uniform sphere's disc-integrated light in the lunar-Lambert model, over its light at full phase
// as a Lambert sphere (2/3): L Phi_LS(a) + 2/3 (1 - L) Phi_L(a), with the Lommel-Seeliger and
// Lambert phase functions (scene/planet_magnitude). L = 0: 2/3 Phi_L.
double lunar_lambert_disc_integral(double phase_rad, double limb_weight);

// max(2 sigma, 4 pixels of the cluster's coarsest channel).
double point_to_disc_start_rad(double psf_sigma_rad, double coarsest_pixel_rad);

}  // namespace cupola

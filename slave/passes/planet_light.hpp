#pragma once
// How much light a planet or moon sends to the camera, and whether it is drawn as a point, as a
// disc, or as both fading into each other. Decided once per frame from the snapshot and from
// cluster-wide constants (the star PSF's angle, the cluster's coarsest pixel), so every channel
// draws a body alike.
//
// The light: for a planet with a measured phase curve (scene/planet_magnitude, Mallama & Hilton
// 2018) its V magnitude, as a flux in scene units: the Sun's irradiance at 1 AU times
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

struct PlanetLight {
    double flux = 0.0;         // scene units x sr at the camera: the whole body
    double disc_scale = 1.0;   // multiplies the Lambert disc's radiance (body.frag u_lit)
    double disc_weight = 1.0;  // 0: a point only; 1: the disc only
    double point_sigma_rad = 0.0;
    glm::dvec3 unit_color{1.0};  // the map's mean colour at unit luminance
    // Small enough on every channel (below 8 x handover_start) for body.frag to antialias its limb
    // and shade a limb pixel inside it; a large disc keeps the exact per-pixel hit.
    bool small_disc = false;
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

struct PlanetLightInputs {
    glm::dvec3 sun_position_m{0.0};
    double sun_irradiance_1au = 0.0;  // scene units; 0: no Sun (no light)
    glm::dvec3 camera_position_m{0.0};
    glm::dvec3 map_mean_rgb{1.0};             // linear, tint included, over the sphere's area
    const LuminanceGrid* map_grid = nullptr;  // its luminance by cell (tint included); null: uniform
    double psf_sigma_rad = 0.0;
    double handover_start_rad = 0.0;
};

PlanetLight planet_light(const BodyConfig& body, const BodyState& state, const PlanetLightInputs& in);

// The grid of an image of width x height linear RGB (body_texture's BodyImage layout), times tint.
LuminanceGrid luminance_grid(int width, int height, const std::vector<float>& rgb, const glm::dvec3& tint);

// How the lit, visible part of the map compares with a uniform map of its mean: the sum over the
// grid of luminance x cos i x cos e, over the same sum with every cell at the mean (1 without a grid).
double lit_map_ratio(const LuminanceGrid* grid, double mean_luminance, const glm::dvec3& to_sun_body,
                     const glm::dvec3& to_camera_body);

// max(2 sigma, 4 pixels of the cluster's coarsest channel).
double point_to_disc_start_rad(double psf_sigma_rad, double coarsest_pixel_rad);

}  // namespace cupola

#pragma once
// A planet's rings reduced to what the renderer reads, by radius: their normal optical depth
// (RingConfig: tau = optical_depth x v^2) and their particles' relative albedo (v), where v is the
// map's linear value, each column averaged over its rows. The map is a picture of the lit face, so
// v sets both how much the rings block and how bright their particles are (the A ring is darker
// than the B ring for both reasons). A clear texel at each end lets filtering fade the edges, and
// a mipmap chain lets rings a few pixels across read the mean their pixels span.
#include <glm/glm.hpp>

#include <vector>

#include "config/scene_config.hpp"
#include "image/mip_chain.hpp"
#include "passes/body_texture.hpp"

namespace cupola {

struct RingProfile {
    std::vector<float> tau;                         // texels: 0, the map's columns, 0
    std::vector<float> albedo;                      // v, by the same texels
    std::vector<MipLevel> mips;                     // levels 1.. of texels_rgb() as an image of one row
    double inner_radius = 0.0, outer_radius = 0.0;  // what the map's columns span, in planet radii

    // The texture coordinate s = r a + b of radius r (planet radii): the first column's centre at
    // the inner radius, the last one's at the outer; outside [0, 1] there are no rings.
    glm::dvec2 radius_to_texture() const;
    // tau and the relative albedo at radius r (planet radii), linearly interpolated as the GPU's
    // level 0 reads them; 0 outside the rings.
    double tau_at(double r) const { return at(tau, r); }
    double albedo_at(double r) const { return at(albedo, r); }
    // The texels as the GPU texture takes them: (tau, albedo, 0).
    std::vector<float> texels_rgb() const;

private:
    double at(const std::vector<float>& texels, double r) const;
};

// planet_radius_m: the body's equatorial radius. Throws std::invalid_argument for an empty map.
RingProfile make_ring_profile(const RingConfig& rings, const BodyImage& map, double planet_radius_m);

}  // namespace cupola

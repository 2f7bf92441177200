#pragma once
// Where the glare of each source the master shares (snapshot.glare) lies for one channel, and
// how far it reaches: what the glare passes (glare_halo_pass.hpp, glare_pass.hpp) draw. Every
// channel places every source, also one whose disc is out of its frustum, from the shared
// visible fraction; in per-channel mode (the naive comparison) only while the source's centre is
// in its own frustum, from its own query.
#include <vector>

#include "config/scene_config.hpp"
#include "gl/gl_program.hpp"
#include "passes/channel_view.hpp"
#include "passes/glare_probe.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// One source's glare in the channel frame.
struct GlarePlacement {
    glm::dvec3 center{0.0};  // unit: the source's centre moved toward its visible part
    glm::dvec3 e1{0.0};      // the cluster-wide glare frame's axes (common/glare/glare_frame)
    glm::dvec3 e2{0.0};
    glm::vec3 irradiance{0.0f};  // rgb: irradiance x visible fraction
    double extent_rad = 0.0;     // nothing beyond this angle from the centre
};

// The angle beyond which a source's glare stays below a quarter of glare.min_display on the
// dome (at most glare.extent_deg): fainter sources get smaller billboards.
double glare_extent_rad(const GlareConfig& config, const GlareSource& source, double exposure);

// The sources whose glare may reach this channel (a generous cone test), in the snapshot's order.
std::vector<GlarePlacement> place_glare(const GlareConfig& config, const ChannelView& view, const Snapshot& snap,
                                        const GlareProbe& probe);

// Sets u_glare (all but extent_rad, which is per source) of a program in use.
void set_glare_params(const GlProgram& program, const GlareConfig& config, float phase);

// Sets u_glare.extent_rad, u_center, u_e1, u_e2 and u_irradiance of a program in use.
void set_glare_placement(const GlProgram& program, const GlarePlacement& placement);

}  // namespace cupola

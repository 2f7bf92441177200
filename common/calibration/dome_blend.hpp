#pragma once
// Edge blending of ideal projectors on the dome (common/calibration/ideal_dome.hpp): in the
// overlaps each projector's light is weighted so the light summed over projectors is the content's,
// after every projector's gamma.
//
// Weight of projector i at a dome direction d: w_i(d) = smoothstep(0, ramp_px, e_i(d)), where
// e_i is the distance, in i's raster pixels, from the raster position that lights d to the edge of
// i's lit image (common/calibration/ideal_dome.hpp: raster rectangle, fisheye image circle), and
// w_i = 0 where i does not light d on the screen. The blend is alpha_i(d) = w_i(d) / sum_j w_j(d)
// (1 where projector i alone lights d), the distance-weighted blend of Raskar et al. (1999), section "intensity
// blending". alpha is linear light: the warp pass multiplies the content by it before the projector's encode gamma, so
// each projector emits C * alpha_i and the sum over projectors is C.
#include <vector>

#include "calibration/ideal_dome.hpp"
#include "calibration/projector_warp.hpp"

namespace cupola {

struct BlendRamp {
    double width_px = 64.0;  // distance from the lit edge over which a weight rises from 0 to 1
};

// w_i(d), 0 when projector does not light the direction on the screen.
double blend_weight(const IdealProjector& projector, const glm::dvec3& dome_dir, const BlendRamp& ramp);

// alpha of projector `index` at one of its raster positions (0 where it does not light the screen).
double blend_alpha(const std::vector<IdealProjector>& projectors, size_t index, const glm::dvec2& pixel,
                   const BlendRamp& ramp);

// The alpha map of projector `index`, width x height texels over its raster (texel (x, y) at
// raster position ((x + 0.5) W / width, (y + 0.5) H / height)), row 0 at the top, linear.
BlendMap dome_alpha_map(const std::vector<IdealProjector>& projectors, size_t index, int width, int height,
                        const BlendRamp& ramp);

}  // namespace cupola

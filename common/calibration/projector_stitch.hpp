#pragma once
// The projector frames stitched back onto the dome: the light the audience sees. For each
// domemaster pixel (common/projection/fisheye.hpp) its dome direction; for each ideal projector
// (common/calibration/ideal_dome.hpp) the raster position that lights that point of the sphere;
// the light there (the encoded frame values decoded with the projector's gamma, light = value^gamma,
// interpolated bilinearly between pixel centres as a slightly defocused lens spreads it) summed
// over the projectors. Seamless and equal to the content when the warps and blends are right.
#include <vector>

#include "calibration/ideal_dome.hpp"
#include "image/frame_image.hpp"

namespace cupola {

// Linear light of one projector frame (encoded values, row 0 at the top) at a raster position;
// 0 outside the lit raster.
glm::dvec3 projector_light(const IdealProjector& projector, const Image& frame, double gamma, const glm::dvec2& pixel);

// The light at one dome direction, summed over the projectors (0 off the screen).
glm::dvec3 dome_light(const std::vector<IdealProjector>& projectors, const std::vector<Image>& frames,
                      const std::vector<double>& gammas, const glm::dvec3& dome_dir);

// A size x size domemaster (fov 180, linear light, RGBA, alpha 1 where on the screen).
Image stitch_projector_frames(const std::vector<IdealProjector>& projectors, const std::vector<Image>& frames,
                              const std::vector<double>& gammas, int size);

}  // namespace cupola

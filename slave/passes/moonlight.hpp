#pragma once
// The moonlit sky's light on the slave (common/atmosphere/moonlit_sky.hpp): which body lights the
// night sky this frame, and how much.
#include "atmosphere/moonlit_sky.hpp"
#include "passes/frame_context.hpp"

namespace cupola {

// The brightest planet or moon at the camera (not a star: the Sun is the first light) among those
// whose light is drawn (PlanetLight::flux: its phase curve, or its lit map), in its map's colour,
// times the sunlight left at its centre by the eclipse shadows on it (a Moon in the Earth's umbra
// lights little but its red glow). None when no body sends light.
SkySecondLight brightest_moonlight(const FrameContext& frame);

}  // namespace cupola

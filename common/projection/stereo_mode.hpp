#pragma once
// How a channel shows the two eyes of a stereo pair: one eye (a channel per eye, or mono), both
// packed into one frame (side by side or top and bottom, each eye at full or half resolution), or
// both mixed into one red-cyan anaglyph. The packing says where each eye's image lies in the
// channel's frame; SceneRenderer renders each eye and packs it (slave/stereo_packer).
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace cupola {

enum class StereoMode {
    Mono = 0,            // one image from the head (the point between the eyes)
    Left = 1,            // the left eye alone (its own channel or slave)
    Right = 2,           // the right eye alone
    SideBySide = 3,      // left | right, each eye width x height: the frame is 2 width x height
    SideBySideHalf = 4,  // left | right squeezed into width x height (each eye width / 2 x height)
    TopBottom = 5,       // left over right, each eye width x height: the frame is width x 2 height
    TopBottomHalf = 6,   // left over right squeezed into width x height (each eye width x height / 2)
    Anaglyph = 7,        // one width x height frame for red-cyan glasses (Dubois 2001)
};

// "mono", "left", "right", "side_by_side", "side_by_side_half", "top_bottom", "top_bottom_half",
// "anaglyph" (in StereoMode's order).
const std::vector<std::string>& stereo_mode_names();
// Throws std::invalid_argument naming the word and the choices; "quad_buffer" is refused saying
// why (no EGL or KMS output of this renderer has a quad-buffered surface).
StereoMode stereo_mode_from_name(const std::string& name);

// How many eyes a frame of this mode renders (1 or 2).
int stereo_eye_count(StereoMode m);
// The side of the head the eye `index` (0 .. eye_count - 1) is on: -1 left, +1 right, 0 mono.
double stereo_eye_side(StereoMode m, int index);
// One eye's image size for a channel of width x height (the raster the channel's frustum spans).
glm::ivec2 stereo_eye_size(StereoMode m, int width, int height);
// The frame's size: both eyes packed.
glm::ivec2 stereo_frame_size(StereoMode m, int width, int height);
// Where eye `index` lies in the frame: x, y (GL: y up, so the top half starts at y = eye height),
// width, height. The left eye is on the left, or on top.
glm::ivec4 stereo_eye_viewport(StereoMode m, int index, int width, int height);

}  // namespace cupola

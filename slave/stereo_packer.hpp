#pragma once
// The frame of a stereo channel made of its two eyes (projection/stereo_mode.hpp), on the GPU:
// each eye's render is copied into its part of the frame (side by side, top and bottom), or, for an
// anaglyph, the left eye is kept and mixed with the right through Dubois's matrices
// (shaders/shared/stereo_anaglyph.glsl). The frame is linear RGBA32F like a mono render, so
// everything after it (the warp, the sinks, the files) takes it as it takes a mono frame.
#include <memory>

#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "projection/stereo_mode.hpp"

namespace cupola {

class StereoPacker {
public:
    // width, height: the channel's (stereo_eye_size and stereo_frame_size say the rest).
    StereoPacker(StereoMode mode, int width, int height);
    ~StereoPacker();

    // Eye `index` (0: left, 1: right) has been rendered into `eye` (the eye's size): copied or
    // mixed into the frame.
    void place(int index, const GlTexture& eye);

    const GlTexture& frame_color() const { return frame_.color(0); }
    Image read() const { return frame_.read(); }

private:
    StereoMode mode_;
    int width_, height_;
    GlFramebuffer frame_;
    std::unique_ptr<GlFramebuffer> left_;  // anaglyph: the left eye until the right is drawn
    std::unique_ptr<GlProgram> mix_;       // anaglyph: shaders/stereo_anaglyph.frag
};

}  // namespace cupola

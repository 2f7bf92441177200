#pragma once
// The render targets of one channel and which of them a pass draws into. The scene is drawn
// into colour A (attachment 0 of the scene target) and the G-buffer (attachment 1: reflectance
// and hit distance, for the atmosphere); a pass that reads the colour so far and writes colour
// draws into the other colour texture (ping-pong: A and B each have a framebuffer of their own,
// so no pass samples a texture attached to the framebuffer it draws into); a pass that only
// writes colour (additive) draws into the colour so far. The G-buffer belongs with colour A, so
// no pass may write it once a pass has read the colour (check_order).
#include <cstdint>
#include <memory>
#include <vector>

#include "gl/gl_framebuffer.hpp"
#include "gl/gl_texture.hpp"
#include "image/frame_image.hpp"
#include "passes/render_pass.hpp"

namespace cupola {

class FrameTargets {
public:
    // depth: the scene target gets a depth buffer (the terrain's), cleared every frame.
    FrameTargets(int width, int height, bool depth = false);

    // Binds the scene target and clears it: colour (0, 0, 0, 1), G-buffer distance -1 (nothing
    // drawn); colour A is the colour so far.
    // geometry: clear the G-buffer too (some pass reads it this frame); else it keeps whatever was
    // drawn into it before and no pass may read it. color: clear the colour; else the frame's
    // first draws must write every pixel (the sky drawn first, FrameContext::sky_first).
    void begin_frame(bool geometry = true, bool color = true);
    uint64_t geometry_clears() const { return geometry_clears_; }
    uint64_t color_clears() const { return color_clears_; }
    // Binds what a pass with these reads and writes draws into (unless it is bound already) and
    // returns what it samples. A pass that writes none of the frame's targets binds its own.
    PassInputs bind_for(const PassIo& io);
    // After a draw: a pass that read the colour and wrote colour leaves its output the colour so far.
    void drawn(const PassIo& io);
    // The colour so far, row 0 at the top (glReadPixels).
    Image read() const;
    // The G-buffer (reflectance, distance), row 0 at the top.
    Image read_geometry() const { return scene_.read(1); }
    // The texture holding the colour so far (GL row 0 at the bottom), for the output stage.
    const GlTexture& color() const { return current_->color(0); }

    // Throws std::logic_error naming the passes when they cannot share these targets in this
    // order: a pass reading what it writes, or writing the G-buffer after a pass read the colour.
    static void check_order(const std::vector<std::unique_ptr<RenderPass>>& passes);

private:
    const GlFramebuffer& other() const { return current_ == &a_ ? b_ : a_; }

    GlTexture color_a_, color_b_, geometry_;
    GlFramebuffer scene_, a_, b_;  // scene_: colour A and the G-buffer
    const GlFramebuffer* current_ = &a_;
    const GlFramebuffer* bound_ = nullptr;
    uint64_t geometry_clears_ = 0, color_clears_ = 0;
};

}  // namespace cupola

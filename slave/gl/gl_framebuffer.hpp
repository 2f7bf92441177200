#pragma once
// An offscreen framebuffer (RAII) rendering into RGBA32F textures, read back as a linear Image.
// Either it owns its single colour texture, or it renders into textures owned elsewhere, so
// that one texture can be the target of one framebuffer and sampled while another is bound
// (ping-pong passes) without a feedback loop.
#include <glm/glm.hpp>

#include <memory>
#include <vector>

#include "gl/gl_api.hpp"
#include "gl/gl_texture.hpp"
#include "image/frame_image.hpp"

namespace cupola {

class GlFramebuffer {
public:
    // One RGBA32F colour texture of its own, attachment 0.
    GlFramebuffer(int width, int height);
    // colors[i] (RGBA32F, all the same size; not owned, they must outlive the framebuffer) as
    // colour attachment i.
    explicit GlFramebuffer(const std::vector<const GlTexture*>& colors);
    ~GlFramebuffer();
    GlFramebuffer(const GlFramebuffer&) = delete;
    GlFramebuffer& operator=(const GlFramebuffer&) = delete;

    // Binds for drawing into every attachment and sets the viewport to the whole framebuffer.
    void bind() const;
    // Draws into attachments [0, count) only; the others keep their contents (for shaders that
    // write fewer outputs: an unwritten output leaves its attachment undefined).
    void draw_buffers(int count) const;
    // Clears one colour attachment (and re-enables drawing into every attachment).
    void clear(int attachment, const glm::vec4& value) const;
    // Adds a DEPTH_COMPONENT32F renderbuffer of its own (once), and clears it to 1.
    void add_depth();
    void clear_depth() const;
    bool has_depth() const { return depth_ != 0; }
    // Reads a colour attachment (0 by default); row 0 of the result is the TOP row.
    Image read(int attachment = 0) const;

    const GlTexture& color(int attachment) const { return *colors_.at(static_cast<size_t>(attachment)); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    void attach();
    std::unique_ptr<GlTexture> owned_;
    std::vector<const GlTexture*> colors_;
    GLuint fbo_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
};

// Keeps the draw framebuffer binding and the viewport of its construction, and puts them back when
// it goes out of scope: for a draw into a target of its own in the middle of another's pass.
class DrawTargetRestorer {
public:
    DrawTargetRestorer() {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
    }
    ~DrawTargetRestorer() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(framebuffer_));
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    }
    DrawTargetRestorer(const DrawTargetRestorer&) = delete;
    DrawTargetRestorer& operator=(const DrawTargetRestorer&) = delete;

private:
    GLint framebuffer_ = 0, viewport_[4] = {0, 0, 0, 0};
};

}  // namespace cupola

#include "gl/gl_framebuffer.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace cupola {

GlFramebuffer::GlFramebuffer(int width, int height)
    : owned_(std::make_unique<GlTexture>(width, height, nullptr, GL_NEAREST)),
      colors_{owned_.get()},
      width_(width),
      height_(height) {
    attach();
}

GlFramebuffer::GlFramebuffer(const std::vector<const GlTexture*>& colors) : colors_(colors) {
    if (colors_.empty() || colors_.size() > 8) throw std::runtime_error("a framebuffer needs 1 to 8 colour textures");
    width_ = colors_[0]->width();
    height_ = colors_[0]->height();
    for (const GlTexture* t : colors_)
        if (t->width() != width_ || t->height() != height_)
            throw std::runtime_error("framebuffer textures differ in size");
    attach();
}

void GlFramebuffer::attach() {
    glCreateFramebuffers(1, &fbo_);
    for (size_t i = 0; i < colors_.size(); ++i)
        glNamedFramebufferTexture(fbo_, static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i), colors_[i]->id(), 0);
    draw_buffers(static_cast<int>(colors_.size()));
    const GLenum st = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        glDeleteFramebuffers(1, &fbo_);
        throw std::runtime_error("RGBA32F framebuffer " + std::to_string(width_) + "x" + std::to_string(height_) +
                                 " is incomplete (status " + std::to_string(st) + ")");
    }
    gl::check("framebuffer creation");
}

GlFramebuffer::~GlFramebuffer() {
    glDeleteFramebuffers(1, &fbo_);
    if (depth_) glDeleteRenderbuffers(1, &depth_);
}

void GlFramebuffer::add_depth() {
    if (depth_) return;
    glCreateRenderbuffers(1, &depth_);
    glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT32F, width_, height_);
    glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    gl::check("framebuffer depth");
}

void GlFramebuffer::clear_depth() const {
    const float one = 1.0f;
    glClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &one);
}

void GlFramebuffer::bind() const {
    draw_buffers(static_cast<int>(colors_.size()));
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, width_, height_);
}

void GlFramebuffer::draw_buffers(int count) const {
    GLenum bufs[8];
    for (size_t i = 0; i < colors_.size(); ++i)
        bufs[i] = static_cast<int>(i) < count ? static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i) : GL_NONE;
    glNamedFramebufferDrawBuffers(fbo_, static_cast<GLsizei>(colors_.size()), bufs);
}

void GlFramebuffer::clear(int attachment, const glm::vec4& value) const {
    draw_buffers(static_cast<int>(colors_.size()));  // the clear names a draw buffer, not an attachment
    glClearNamedFramebufferfv(fbo_, GL_COLOR, attachment, &value[0]);
}

Image GlFramebuffer::read(int attachment) const {
    Image img;
    img.width = width_;
    img.height = height_;
    std::vector<float> gl_rows(static_cast<size_t>(width_) * height_ * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glReadBuffer(static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + attachment));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, gl_rows.data());
    gl::check("glReadPixels");
    img.rgba.resize(gl_rows.size());
    const size_t row = static_cast<size_t>(width_) * 4;
    for (int y = 0; y < height_; ++y)  // GL row 0 is the bottom
        std::memcpy(&img.rgba[static_cast<size_t>(y) * row], &gl_rows[static_cast<size_t>(height_ - 1 - y) * row],
                    row * sizeof(float));
    return img;
}

}  // namespace cupola

#include "gl_framebuffer.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace cupola {

GlFramebuffer::GlFramebuffer(int width, int height) : width_(width), height_(height) {
    if (width <= 0 || height <= 0)
        throw std::runtime_error("framebuffer size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is not positive");
    glCreateFramebuffers(1, &fbo_);
    glCreateRenderbuffers(1, &color_);
    glNamedRenderbufferStorage(color_, GL_RGBA32F, width, height);
    glCreateRenderbuffers(1, &depth_);
    glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT24, width, height);
    glNamedFramebufferRenderbuffer(fbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
    glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    const GLenum st = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("RGBA32F framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is incomplete (status " + std::to_string(st) + ")");
    gl::check("framebuffer creation");
}

GlFramebuffer::~GlFramebuffer() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteRenderbuffers(1, &color_);
    glDeleteRenderbuffers(1, &depth_);
}

void GlFramebuffer::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, width_, height_);
}

Image GlFramebuffer::read() const {
    Image img;
    img.width = width_;
    img.height = height_;
    std::vector<float> gl_rows(static_cast<size_t>(width_) * height_ * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
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

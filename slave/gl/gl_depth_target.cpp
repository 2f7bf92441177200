#include "gl/gl_depth_target.hpp"

#include <stdexcept>
#include <string>

namespace cupola {

GlDepthTarget::GlDepthTarget(int width, int height) : width_(width), height_(height) {
    glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
    glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &fbo_);
    glNamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
    glNamedFramebufferDrawBuffer(fbo_, GL_NONE);
    glNamedFramebufferReadBuffer(fbo_, GL_NONE);
    const GLenum st = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        glDeleteFramebuffers(1, &fbo_);
        glDeleteTextures(1, &depth_);
        throw std::runtime_error("depth framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is incomplete (status " + std::to_string(st) + ")");
    }
    gl::check("depth target creation");
}

GlDepthTarget::~GlDepthTarget() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &depth_);
}

void GlDepthTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, width_, height_);
}

void GlDepthTarget::clear_depth(float depth) const { glClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &depth); }

}  // namespace cupola

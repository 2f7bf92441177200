#include "stereo_packer.hpp"

#include "gl/gl_api.hpp"
#include "gl/gl_buffer.hpp"

namespace cupola {

namespace {
glm::ivec2 frame_size(StereoMode m, int w, int h) { return stereo_frame_size(m, w, h); }

// Copies the whole of `from` into `to` at the region (x, y, width, height), texel for texel.
void copy_into(const GlTexture& from, const GlFramebuffer& to, const glm::ivec4& region) {
    glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, 0, 0, 0, to.color(0).id(), GL_TEXTURE_2D, 0, region.x, region.y, 0,
                       region.z, region.w, 1);
}
}  // namespace

StereoPacker::StereoPacker(StereoMode mode, int width, int height)
    : mode_(mode),
      width_(width),
      height_(height),
      frame_(frame_size(mode, width, height).x, frame_size(mode, width, height).y) {
    if (mode_ == StereoMode::Anaglyph) {
        left_ = std::make_unique<GlFramebuffer>(width, height);
        mix_ = std::make_unique<GlProgram>("fullscreen.vert", "stereo_anaglyph.frag");
    }
}

StereoPacker::~StereoPacker() = default;

void StereoPacker::place(int index, const GlTexture& eye) {
    if (mode_ != StereoMode::Anaglyph) {
        copy_into(eye, frame_, stereo_eye_viewport(mode_, index, width_, height_));
        return;
    }
    if (index == 0) {
        copy_into(eye, *left_, {0, 0, width_, height_});
        return;
    }
    const DrawTargetRestorer restore;
    frame_.bind();
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    mix_->use();
    mix_->set("u_left", 0);
    mix_->set("u_right", 1);
    glBindTextureUnit(0, left_->color(0).id());
    glBindTextureUnit(1, eye.id());
    GlEmptyVertexArray triangle;
    triangle.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace cupola

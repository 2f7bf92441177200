#include "gl_texture.hpp"

namespace cupola {

GlTexture::GlTexture(int width, int height, const std::vector<float>& rgb) {
    glCreateTextures(GL_TEXTURE_2D, 1, &id_);
    glTextureStorage2D(id_, 1, GL_RGB16F, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(id_, 0, 0, 0, width, height, GL_RGB, GL_FLOAT, rgb.data());
    glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id_, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl::check("texture upload");
}

GlTexture::~GlTexture() { glDeleteTextures(1, &id_); }

}  // namespace cupola

#include "gl/gl_texture.hpp"

#include <algorithm>

#include <stdexcept>
#include <string>

namespace cupola {

namespace {
void check_size(int width, int height) {
    if (width <= 0 || height <= 0)
        throw std::runtime_error("texture size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is not positive");
}
}  // namespace

GlTexture::GlTexture(int width, int height, const std::vector<float>& rgb, const std::vector<MipLevel>& mips)
    : width_(width), height_(height) {
    check_size(width, height);
    glCreateTextures(GL_TEXTURE_2D, 1, &id_);
    int levels = 1;
    while ((std::max(width, height) >> levels) > 0) ++levels;
    glTextureStorage2D(id_, levels, GL_RGB16F, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(id_, 0, 0, 0, width, height, GL_RGB, GL_FLOAT, rgb.data());
    if (static_cast<int>(mips.size()) != levels - 1)
        throw std::invalid_argument("texture " + std::to_string(width) + "x" + std::to_string(height) + ": " +
                                    std::to_string(mips.size()) + " mipmap levels given, " +
                                    std::to_string(levels - 1) + " needed");
    for (size_t i = 0; i < mips.size(); ++i)
        glTextureSubImage2D(id_, static_cast<GLint>(i + 1), 0, 0, mips[i].width, mips[i].height, GL_RGB, GL_FLOAT,
                            mips[i].rgb.data());
    glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id_, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl::check("texture upload");
}

GlTexture::GlTexture(int width, int height, const glm::vec4* rgba, GLenum filter) : width_(width), height_(height) {
    check_size(width, height);
    glCreateTextures(GL_TEXTURE_2D, 1, &id_);
    glTextureStorage2D(id_, 1, GL_RGBA32F, width, height);
    if (rgba) {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage2D(id_, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba);
    }
    glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(id_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl::check("RGBA32F texture " + std::to_string(width) + "x" + std::to_string(height));
}

GlTexture::~GlTexture() { glDeleteTextures(1, &id_); }

}  // namespace cupola

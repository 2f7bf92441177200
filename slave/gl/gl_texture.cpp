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

// The levels of a full mipmap chain, level 0 down to 1x1.
int full_mip_count(int width, int height) {
    int levels = 1;
    while ((std::max(width, height) >> levels) > 0) ++levels;
    return levels;
}

// The first channel of each texel of an RGB image.
std::vector<float> red_of(const std::vector<float>& rgb) {
    std::vector<float> red(rgb.size() / 3);
    for (size_t i = 0; i < red.size(); ++i) red[i] = rgb[3 * i];
    return red;
}

void upload_level(GLuint id, int level, int width, int height, const std::vector<float>& rgb, bool grey) {
    if (grey)
        glTextureSubImage2D(id, level, 0, 0, width, height, GL_RED, GL_FLOAT, red_of(rgb).data());
    else
        glTextureSubImage2D(id, level, 0, 0, width, height, GL_RGB, GL_FLOAT, rgb.data());
}
}  // namespace

GlTexture::GlTexture(int width, int height, const std::vector<float>& rgb, const std::vector<MipLevel>& mips,
                     Channels channels)
    : width_(width), height_(height) {
    check_size(width, height);
    glCreateTextures(GL_TEXTURE_2D, 1, &id_);
    const int levels = full_mip_count(width, height);
    const bool grey = channels == Channels::Grey;
    glTextureStorage2D(id_, levels, grey ? GL_R16F : GL_RGB16F, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    upload_level(id_, 0, width, height, rgb, grey);
    if (static_cast<int>(mips.size()) != levels - 1)
        throw std::invalid_argument("texture " + std::to_string(width) + "x" + std::to_string(height) + ": " +
                                    std::to_string(mips.size()) + " mipmap levels given, " +
                                    std::to_string(levels - 1) + " needed");
    for (size_t i = 0; i < mips.size(); ++i)
        upload_level(id_, static_cast<GLint>(i + 1), mips[i].width, mips[i].height, mips[i].texels, grey);
    if (grey) {
        glTextureParameteri(id_, GL_TEXTURE_SWIZZLE_G, GL_RED);
        glTextureParameteri(id_, GL_TEXTURE_SWIZZLE_B, GL_RED);
    }
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

GlTexture::GlTexture(int width, int height, const std::vector<std::vector<uint8_t>>& levels)
    : width_(width), height_(height) {
    check_size(width, height);
    const int count = full_mip_count(width, height);
    if (static_cast<int>(levels.size()) != count)
        throw std::invalid_argument("coverage texture " + std::to_string(width) + "x" + std::to_string(height) + ": " +
                                    std::to_string(levels.size()) + " levels given, " + std::to_string(count) +
                                    " needed");
    glCreateTextures(GL_TEXTURE_2D, 1, &id_);
    glTextureStorage2D(id_, count, GL_R8, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int l = 0, w = width, h = height; l < count; ++l, w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        if (levels[static_cast<size_t>(l)].size() != static_cast<size_t>(w) * h)
            throw std::invalid_argument("coverage texture level " + std::to_string(l) + ": " +
                                        std::to_string(levels[static_cast<size_t>(l)].size()) + " values for " +
                                        std::to_string(w) + "x" + std::to_string(h));
        glTextureSubImage2D(id_, l, 0, 0, w, h, GL_RED, GL_UNSIGNED_BYTE, levels[static_cast<size_t>(l)].data());
    }
    glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl::check("coverage texture " + std::to_string(width) + "x" + std::to_string(height));
}

GlTexture::~GlTexture() { glDeleteTextures(1, &id_); }

}  // namespace cupola

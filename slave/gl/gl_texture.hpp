#pragma once
// 2D float textures (RAII):
//  - body surface maps: RGB16F with a full mipmap chain built on the CPU (image/mip_chain; a
//    small disc samples the level its pixels span), trilinear filtering, repeating in s
//    (longitude), clamped in t;
//  - RGBA32F data and render targets: clamped to the edge in both directions, linear or nearest
//    filtering, one level (sampled with textureLod / texelFetch).
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "gl/gl_api.hpp"
#include "image/mip_chain.hpp"

namespace cupola {

class GlTexture {
public:
    // rgb: width*height*3 linear floats, row 0 first (texture coordinate t = 0); mips: its levels
    // 1.. as box_filter_mip_chain makes them (std::invalid_argument when the count is wrong).
    // Grey: a map whose three channels are equal is kept in one (R16F, read back as r = g = b):
    // a third of the memory, and of the bytes each fetch reads.
    enum class Channels { Rgb, Grey };
    GlTexture(int width, int height, const std::vector<float>& rgb, const std::vector<MipLevel>& mips,
              Channels channels = Channels::Rgb);
    // RGBA32F; rgba: width*height texels, row 0 first, or nullptr for an uninitialised render target.
    GlTexture(int width, int height, const glm::vec4* rgba, GLenum filter);
    // 8-bit coverage (a glyph atlas): R8, read back as r, trilinear filtering, clamped to the edge.
    // levels: the full chain, level 0 (width*height values, row 0 first) down to 1x1, each level
    // max(1, n / 2) of the one before (std::invalid_argument when a level is missing or mis-sized).
    GlTexture(int width, int height, const std::vector<std::vector<uint8_t>>& levels);
    ~GlTexture();
    GlTexture(const GlTexture&) = delete;
    GlTexture& operator=(const GlTexture&) = delete;

    void bind(GLuint unit) const { glBindTextureUnit(unit, id_); }
    GLuint id() const { return id_; }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    GLuint id_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace cupola

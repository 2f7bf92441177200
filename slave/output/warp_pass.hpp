#pragma once
// The projector's last pass (stand-in with the warp pass's interface): until a calibration is
// applied it maps the channel render 1:1 onto the projector raster, times the exposure, into a
// linear RGBA32F target and an sRGB-encoded RGBA8 target (the bytes a projector is sent).
#include <optional>

#include "calibration/projector_warp.hpp"
#include "gl/gl_api.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_texture.hpp"
#include "image/frame_image.hpp"

namespace cupola {

struct WarpOptions {};

// An RGBA8 render target (RAII): what live outputs blit to their surfaces.
class EncodedTarget {
public:
    EncodedTarget(int width, int height);
    ~EncodedTarget();
    EncodedTarget(const EncodedTarget&) = delete;
    EncodedTarget& operator=(const EncodedTarget&) = delete;
    void bind() const;  // for drawing and reading, viewport = the whole target
    EncodedImage read() const;
    GLuint texture() const { return texture_; }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    GLuint texture_ = 0, fbo_ = 0;
    int width_ = 0, height_ = 0;
};

class WarpPass {
public:
    WarpPass(std::optional<ProjectorWarp> warp, int content_width, int content_height, WarpOptions options = {});
    ~WarpPass();
    WarpPass(const WarpPass&) = delete;
    WarpPass& operator=(const WarpPass&) = delete;

    // Draws the projector frame from the channel's final colour (linear) times the exposure.
    void draw(const GlTexture& content, double exposure);
    const GlFramebuffer& linear_framebuffer() const { return linear_; }
    const EncodedTarget& encoded_framebuffer() const { return encoded_; }
    Image read_linear() const { return linear_.read(); }
    EncodedImage read_encoded() const { return encoded_.read(); }

private:
    GlFramebuffer linear_;
    EncodedTarget encoded_;
    GLuint both_ = 0;  // a framebuffer with both: attachment 0 linear, 1 encoded
    GLuint program_ = 0;
    GlEmptyVertexArray vao_;
};

}  // namespace cupola

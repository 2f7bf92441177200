#pragma once
// An offscreen framebuffer: RGBA32F colour + 24-bit depth (RAII), read back as a linear Image.
#include "gl_api.hpp"
#include "image/frame_image.hpp"

namespace cupola {

class GlFramebuffer {
public:
    GlFramebuffer(int width, int height);
    ~GlFramebuffer();
    GlFramebuffer(const GlFramebuffer&) = delete;
    GlFramebuffer& operator=(const GlFramebuffer&) = delete;

    void bind() const;
    // Reads the colour buffer; row 0 of the result is the TOP row.
    Image read() const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    GLuint fbo_ = 0, color_ = 0, depth_ = 0;
    int width_, height_;
};

}  // namespace cupola

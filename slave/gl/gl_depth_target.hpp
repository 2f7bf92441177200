#pragma once
// A depth-only offscreen target (RAII): one DEPTH_COMPONENT32F texture, no colour. What the
// glare probe draws its occluders into before it runs its occlusion queries.
#include "gl/gl_api.hpp"

namespace cupola {

class GlDepthTarget {
public:
    GlDepthTarget(int width, int height);
    ~GlDepthTarget();
    GlDepthTarget(const GlDepthTarget&) = delete;
    GlDepthTarget& operator=(const GlDepthTarget&) = delete;

    // Binds for drawing (no colour buffers) and sets the viewport to the whole target.
    void bind() const;
    void clear_depth(float depth = 1.0f) const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    GLuint fbo_ = 0, depth_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace cupola

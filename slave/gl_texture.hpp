#pragma once
// A 2D RGB float texture (RAII), linear filtering, repeating in s, clamped in t.
#include <vector>

#include "gl_api.hpp"

namespace cupola {

class GlTexture {
public:
    // rgb: width*height*3 linear floats, row 0 first (texture coordinate t = 0).
    GlTexture(int width, int height, const std::vector<float>& rgb);
    ~GlTexture();
    GlTexture(const GlTexture&) = delete;
    GlTexture& operator=(const GlTexture&) = delete;
    void bind(GLuint unit) const { glBindTextureUnit(unit, id_); }

private:
    GLuint id_ = 0;
};

}  // namespace cupola

#include "gl/gl_api.hpp"

#include <cstdio>
#include <stdexcept>

namespace cupola::gl {
void check(const std::string& what) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) return;
    while (glGetError() != GL_NO_ERROR) {}
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%04x", e);
    throw std::runtime_error(what + ": GL error " + buf);
}
}  // namespace cupola::gl

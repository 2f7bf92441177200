#pragma once
// OpenGL 4.5 core declarations. Functions come from libOpenGL (libglvnd), which dispatches to
// the vendor library of the current EGL context (Mesa llvmpipe here, NVIDIA on GPU nodes).
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace cupola::gl {
// Throws std::runtime_error("<what>: GL error 0x....") if glGetError reports anything.
void check(const std::string& what);
}  // namespace cupola::gl

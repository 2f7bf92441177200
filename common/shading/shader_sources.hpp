#pragma once
// Shader texts embedded at build time (shaders/CMakeLists.txt). Names are paths relative to
// shaders/, e.g. "stars.vert" or "shared/limb_darkening.glsl".
#include <string>

namespace cupola {
const std::string& shader_source(const std::string& name);
}

#pragma once
// The shading functions of shaders/shared/*.glsl, compiled as C++ (the GPU runs the same text:
// SceneRenderer prepends these files to its shaders). See glsl_compat.hpp for the rules. Both
// sides take the files from one list, CUPOLA_SHARED_SHADING_FILES in shaders/CMakeLists.txt,
// which generates the included .inc files.
#include "shading/glsl_compat.hpp"
#include "shading/shared_types.hpp"  // data types first, outside the anonymous namespace

namespace cupola::shading {
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
#endif
namespace {
#include "shading/shared_functions.inc"  // generated: every other file of the list, in its order
}  // namespace
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
}  // namespace cupola::shading

namespace cupola {
// The shared files in the order a shader needs them prepended (after its #version line): the
// same files, in the same order, as the C++ build above.
inline const char* const kSharedShadingFiles[] = {
#include "shading/shared_files.inc"  // generated
};
}  // namespace cupola

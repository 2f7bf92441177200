#pragma once
// The plain data types of shaders/shared/*_types.glsl (structs and integer constants such as the
// ECLIPSE_MODE_* numbers), compiled as C++: one type across translation units, unlike the
// functions (shared_shading.hpp). Light enough for any header that needs only these.
#include "shading/glsl_compat.hpp"

namespace cupola::shading {
#include "shading/shared_types.inc"  // generated: the *_types files of CUPOLA_SHARED_SHADING_FILES
}  // namespace cupola::shading

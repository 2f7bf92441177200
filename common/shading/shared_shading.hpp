#pragma once
// The shading functions of shaders/shared/*.glsl, compiled as C++ (the GPU runs the same text:
// SceneRenderer prepends these files to its shaders). See glsl_compat.hpp for the rules.
#include "shading/glsl_compat.hpp"

namespace cupola::shading {
// Data types first, outside the anonymous namespace: one type in every translation unit.
#include "shared/atmosphere_types.glsl"
#include "shared/eclipse_types.glsl"
#include "shared/glare_types.glsl"
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
#endif
namespace {
#include "shared/constants.glsl"
#include "shared/limb_darkening.glsl"
#include "shared/star_psf.glsl"
#include "shared/glare_psf.glsl"
#include "shared/star_color.glsl"
#include "shared/sphere_view.glsl"
#include "shared/channel_ownership.glsl"
#include "shared/eclipse_shadow.glsl"
#include "shared/eclipse_casters.glsl"
#include "shared/atmosphere_params.glsl"
#include "shared/atmosphere_geometry.glsl"
#include "shared/atmosphere_lut_mapping.glsl"
#include "shared/atmosphere_tables.glsl"
#include "shared/atmosphere_sky.glsl"
#include "shared/atmosphere_analytic.glsl"
#include "shared/atmosphere_color.glsl"
}  // namespace
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
}  // namespace cupola::shading

namespace cupola {
// The shared files in the order a shader needs them prepended (after its #version line).
inline const char* const kSharedShadingFiles[] = {
    "shared/atmosphere_types.glsl",  "shared/eclipse_types.glsl",       "shared/glare_types.glsl",
    "shared/constants.glsl",         "shared/limb_darkening.glsl",      "shared/star_psf.glsl",
    "shared/glare_psf.glsl",         "shared/star_color.glsl",          "shared/sphere_view.glsl",
    "shared/channel_ownership.glsl", "shared/eclipse_shadow.glsl",      "shared/eclipse_casters.glsl",
    "shared/atmosphere_params.glsl", "shared/atmosphere_geometry.glsl", "shared/atmosphere_lut_mapping.glsl",
    "shared/atmosphere_tables.glsl", "shared/atmosphere_sky.glsl",      "shared/atmosphere_analytic.glsl",
    "shared/atmosphere_color.glsl"};
}  // namespace cupola

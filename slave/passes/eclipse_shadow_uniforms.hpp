#pragma once
// GPU side of the eclipse shadows (shaders/shared/eclipse_*.glsl): the lookup-table texture of
// the lookup mode, built once for the scene's Sun, and the uniforms every shadowed pass sets
// (u_ecl: the receiver's EclipseCasters from eclipse/shadow_casters.hpp; u_eclipse_lut;
// u_eclipse_lut_size).
#include "config/scene_config.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

class EclipseShadowUniforms {
public:
    explicit EclipseShadowUniforms(double limb_u);
    // The table for the scene's Sun (its limb-darkening coefficient; 0 without a star).
    explicit EclipseShadowUniforms(const SceneConfig& scene);
    // Sets the uniforms on the current program and binds the table to texture unit `unit`.
    void apply(const GlProgram& program, const shading::EclipseCasters& casters, GLuint unit) const;

private:
    GlTexture lut_;
    glm::vec2 lut_size_;
};

}  // namespace cupola

#pragma once
// A star of the scene (BodyKind::Star, the Sun) as a limb-darkened disc with its corona,
// drawn as an analytic sphere on a viewpoint-oriented billboard (shaders/sun.frag,
// shared/limb_darkening.glsl). The Moon, nearer, is drawn over it afterwards (painter's order).
// Drawn by PainterPass (slave/passes/painter_pass.hpp).
#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "passes/beyond_the_air.hpp"
#include "passes/sphere_billboard.hpp"

namespace cupola {

// The corona reaches this many solar radii (shaders/sun.frag's CORONA_EXTENT).
constexpr double kCoronaExtent = 6.0;

class SunPass {
public:
    SunPass();
    // Adds the disc and the corona into the bound framebuffer (and the disc's geometry). sky: the
    // frame's sky was drawn first, and both take the air's transmittance in front of them from it
    // (beyond_the_air.hpp); the bound framebuffer is then the colour alone.
    void draw(const ChannelView& view, const BodyConfig& body, const SphereView& sphere,
              const SkyInFrontSource* sky = nullptr);

private:
    GlProgram program_, after_sky_;
    GlEmptyVertexArray vao_;
};

}  // namespace cupola

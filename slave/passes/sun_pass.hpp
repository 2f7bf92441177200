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
    // weight: the disc's share of the star's light (PlanetLight::disc_weight; the rest is a point);
    // the corona, an extended light of its own, is drawn whole.
    // antialias_limb (a small disc, PlanetLight::small_disc): the limb's coverage of each pixel
    // weights it, and a limb pixel is shaded inside the limb.
    void draw(const ChannelView& view, const BodyConfig& body, const SphereView& sphere,
              const SkyInFrontSource* sky = nullptr, double weight = 1.0, bool antialias_limb = false);

private:
    GlProgram program_, after_sky_;
    GlEmptyVertexArray vao_;
};

}  // namespace cupola

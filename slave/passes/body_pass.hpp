#pragma once
// Planets and moons (for PainterPass, slave/passes/painter_pass.hpp, and the glare probe's
// occluders), analytic ray-sphere on a viewpoint-oriented billboard (no mesh), textured from an
// equirectangular image in the body frame and Lambert-lit by the scene's star:
//   E = pi * L_sun * (1 - u/3) * (R_sun / d_sun)^2,  L = albedo / pi * E * max(cos i, 0) * texture.
// Colour attachment 1 receives the deferred geometry of each covered pixel for the atmosphere
// pass: rgb = diffuse reflectance (albedo * tint * texture, linear), a = hit distance in metres.
#include <map>
#include <memory>

#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/beyond_the_air.hpp"
#include "passes/eclipse_shadow_uniforms.hpp"
#include "passes/frame_context.hpp"
#include "passes/planet_light.hpp"
#include "passes/ring_drawer.hpp"
#include "passes/sphere_billboard.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// Irradiance (scene units) at distance d_m from the light's centre.
double sun_irradiance(const SunLight& sun, double d_m);

class BodyPass {
public:
    explicit BodyPass(const SceneConfig& scene);  // every planet/moon map, once (body_map.hpp: prefetched or prepared)
    // casters: the body's eclipse shadows this frame, in the channel frame (count 0: none).
    // sky: the frame's sky was drawn first; the body replaces it, composed with the air in front
    // of it (beyond_the_air.hpp), and writes no geometry (the bound framebuffer is the colour alone).
    // light: the disc's radiance is scaled by its phase curve and point-to-disc weight
    // (disc_scale x disc_weight), its surface reflects with its limb_weight and is lit by its
    // planetshine. A small disc (PlanetLight::small_disc) has the colour blended by the limb's
    // coverage of each pixel, and a limb pixel shaded inside the limb.
    void draw(const ChannelView& view, const BodyConfig& body, const BodyState& state, const SphereView& sphere,
              const SunLight& sun, const EclipseShadowUniforms& shadows, const shading::EclipseCasters& casters,
              const SkyInFrontSource* sky = nullptr, const PlanetLight& light = PlanetLight{});
    // A ringed planet's rings (ring_drawer.hpp), after the planet; nothing for a body without.
    void draw_rings(const ChannelView& view, const FrameBody& body, const SunLight& sun,
                    const SkyInFrontSource* sky) const {
        rings_.draw(view, body, sun, sky);
    }
    const RingDrawer& rings() const { return rings_; }
    // The mean linear colour of a body's map over its sphere, tint included (body_map_mean_rgb);
    // black for a body without one.
    glm::dvec3 map_mean_rgb(uint16_t body_id) const;
    // Its luminance on a coarse grid (planet_light.hpp); null for a body without a map.
    const LuminanceGrid* map_grid(uint16_t body_id) const;
    // A body's map (linear RGB), or null for a body without one.
    const GlTexture* texture(uint16_t body_id) const;
    // The matrix body.frag takes the map's coordinates with (shared/sphere_view.glsl, body_map_uv).
    static glm::mat3 channel_to_body(const ChannelView& view, const BodyState& state);
    // The map level one pixel spans at the disc's centre, for a map map_width texels around: a small
    // disc samples a coarser level. The atmosphere's look-up takes the same when it draws the surface.
    static double map_lod(const ChannelView& view, const SphereView& sphere, const BodyConfig& body, int map_width);

private:
    // The body.frag variants the scene needs, by bits (body_pass.cpp, variants_needed): with
    // eclipse shadows (a body without an atmosphere, in a shadow) and without (the atmosphere pass
    // relights the surface of a body that has one, shadows included); drawn in the usual order or
    // after the sky; a sphere or an oblate spheroid; with its rings' shadow.
    std::map<unsigned, std::unique_ptr<GlProgram>> programs_;
    const GlProgram& program(bool oblate, bool after_sky, bool shadowed, bool rings) const;
    RingDrawer rings_;
    // Sets the stretched-sphere uniforms of an oblate body (body.frag, BODY_OBLATE) and returns the
    // sphere as that frame sees it (its cover unchanged).
    static SphereView oblate_sphere(const GlProgram& program, const ChannelView& view, const BodyConfig& body,
                                    const BodyState& state, const SphereView& sphere);
    GlEmptyVertexArray vao_;
    std::map<uint16_t, std::unique_ptr<GlTexture>> textures_;
    std::map<uint16_t, glm::dvec3> map_means_;
    std::map<uint16_t, LuminanceGrid> map_grids_;
};

}  // namespace cupola

#pragma once
// A planet's atmosphere, deferred, over the whole channel (shaders/atmosphere.frag).
// Reads the scene colour and the deferred geometry the body pass wrote (reflectance, hit
// distance), and writes a new colour target: the planet's own surface relit through the
// atmosphere (direct Sun + sky light), everything behind the air attenuated, plus in-scatter.
// The model is the production atmosphere (common/atmosphere/production_model.hpp) running the
// same shared code as the CPU; its tables are loaded from the disk cache or built at start-up.
//
// Units: the shared code works per unit solar irradiance and atm_samples_to_xyz() turns that
// into cd m^-2 for the physical solar spectrum, whose illuminance E_phys is the sum of the
// colour weights' Y (atmosphere::physical_solar_illuminance). The scene's Sun has the irradiance
// E_scene = pi L (R/D)^2 (1 - u/3) at the planet (sun_irradiance(), as the body pass lights it);
// solar_scale = E_scene / E_phys puts the atmosphere in scene units, consistent with the Sun disc
// and the Lambert-lit bodies.
#include <map>
#include <memory>
#include <vector>

#include "atmosphere/production_model.hpp"
#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/body_pass.hpp"
#include "passes/eclipse_shadow_uniforms.hpp"
#include "passes/render_pass.hpp"
#include "passes/sphere_billboard.hpp"
#include "projection/channel_frustum.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// One body's atmosphere: the production model (tables from the disk cache, or built) and its
// tables and colour weights as RGBA32F textures.
class GpuAtmosphere {
public:
    explicit GpuAtmosphere(const BodyConfig& body);
    const atmosphere::ProductionAtmosphere& model() const { return model_; }
    double top_radius_m() const { return model_.parameters().top_radius; }
    // Binds transmittance, multiple scattering, irradiance and colour weights to units
    // first_unit .. first_unit + 3.
    void bind(GLuint first_unit) const;

private:
    atmosphere::ProductionAtmosphere model_;
    GlTexture transmittance_, multiple_scattering_, irradiance_, color_weights_;
};

// True when a sphere (centre in the channel frame, metres) lies entirely outside the channel's
// four side planes through the camera: conservative (a sphere near a corner may be kept).
bool sphere_outside_frustum(const ChannelFrustum& frustum, const glm::dvec3& center_channel_m, double radius_m);

class AtmospherePass : public RenderPass {
public:
    using Atmospheres = std::map<uint16_t, std::unique_ptr<GpuAtmosphere>>;  // by body id

    // atmospheres: every body's that has one (not empty).
    AtmospherePass(Atmospheres atmospheres, const EclipseShadowUniforms& shadows);

    // In the pass list: one draw per body with an atmosphere whose top-of-atmosphere sphere can
    // touch the frustum, far to near, each over everything drawn so far: reads the colour and the
    // G-buffer, writes the colour (ping-pong).
    std::string name() const override { return "atmosphere"; }
    PassIo io() const override { return {.reads_color = true, .reads_geometry = true, .writes_color = true}; }
    int prepare(const FrameContext& frame) override;
    void draw(const PassInputs& in, int step) override;

    const Atmospheres& atmospheres() const { return atmospheres_; }
    long draws_run() const { return run_; }          // summed over frames
    long draws_skipped() const { return skipped_; }  // atmosphere entirely outside the frustum

    // One body's atmosphere. Draws into the bound framebuffer (the whole viewport). scene: colour so far; geometry: the
    // body pass's (reflectance, distance), distance < 0 where nothing was drawn.
    void draw(const ChannelView& view, const GpuAtmosphere& atmosphere, const BodyState& state,
              const SphereView& sphere, const SunLight& sun, const GlTexture& scene, const GlTexture& geometry,
              const EclipseShadowUniforms& shadows, const shading::EclipseCasters& casters);

private:
    struct Layer {
        const FrameBody* body;
        const GpuAtmosphere* atmosphere;
    };
    Atmospheres atmospheres_;
    const EclipseShadowUniforms& shadows_;
    GlProgram program_;
    GlEmptyVertexArray vao_;
    const FrameContext* frame_ = nullptr;
    std::vector<Layer> layers_;  // this frame's draws
    long run_ = 0, skipped_ = 0;
};

}  // namespace cupola

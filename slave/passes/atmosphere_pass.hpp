#pragma once
// A planet's atmosphere, deferred, over the pixels that can see its shell. Reads the deferred
// geometry the body pass wrote (reflectance, hit distance) and blends into the colour in place
// (dual-source blending: colour = in-scatter + colour so far x transmittance, or the relit
// surface): the planet's own surface relit through the atmosphere (direct Sun + sky light),
// everything behind the air attenuated, plus in-scatter. Only the screen bounds of the
// top-of-atmosphere sphere are drawn (a scissor; sphere_screen_bounds.hpp).
// The model is the production atmosphere (common/atmosphere/production_model.hpp) running the
// same shared code as the CPU; its tables are loaded from the disk cache or built at start-up.
// A sky-view level looks the sky up in a table rendered once per frame for the whole dome
// (sky_view_gpu.hpp, shaders/atmosphere_lookup.frag); the march levels, and any frame in which
// an eclipse shadow falls on this planet, march every pixel (shaders/atmosphere.frag).
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

#include "atmosphere/air_disc.hpp"
#include "atmosphere/production_model.hpp"
#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/beyond_the_air.hpp"
#include "passes/body_pass.hpp"
#include "passes/eclipse_shadow_uniforms.hpp"
#include "passes/glare_halo_pass.hpp"
#include "atmosphere/moonlit_sky.hpp"
#include "passes/render_pass.hpp"
#include "passes/sky_view_gpu.hpp"
#include "passes/sphere_billboard.hpp"
#include "passes/sphere_screen_bounds.hpp"
#include "passes/star_sky.hpp"
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
    // The sky-view table of a sky-view level (null for the march levels), created on first use.
    GpuSkyViewTable* sky_view();
    const GpuSkyViewTable* sky_view_if_made() const { return sky_view_.get(); }
    // The moonlit sky's table (atmosphere/moonlit_sky.hpp): the same table for the Moon's zenith angle, created
    // on first use (null for the march levels).
    GpuSkyViewTable* moon_sky_view();
    const GpuSkyViewTable* moon_sky_view_if_made() const { return moon_sky_view_.get(); }
    // The second wavelength triplet's transmittance, multiple scattering and irradiance (a
    // six-wavelength sky-view level; 1x1 placeholders otherwise) to units first_unit .. + 2.
    void bind_second(GLuint first_unit) const;
    // The whole disc's light for a distant observer by phase angle (atmosphere/air_disc.hpp),
    // computed on first use: what the planet's point carries.
    const atmosphere::AirDiscCurve& disc_curve();

private:
    atmosphere::ProductionAtmosphere model_;
    std::unique_ptr<atmosphere::AirDiscCurve> disc_curve_;
    GlTexture transmittance_, multiple_scattering_, irradiance_, color_weights_;
    GlTexture transmittance2_, multiple_scattering2_, irradiance2_;
    std::unique_ptr<GpuSkyViewTable> sky_view_, moon_sky_view_;
};

// True when a sphere (centre in the channel frame, metres) lies entirely outside the channel's
// four side planes through the camera: conservative (a sphere near a corner may be kept).
bool sphere_outside_frustum(const ChannelFrustum& frustum, const glm::dvec3& center_channel_m, double radius_m);

// What a draw adds to the look-up besides the sky: the glare's halo, the planet's surface.
struct AtmosphereDrawExtras {
    const GlareHaloPass* halo = nullptr;
    const GlTexture* surface_map = nullptr;
    glm::mat3 channel_to_body{1.0f};
    glm::vec3 surface_reflectance{0.0f};  // albedo * tint, as the body pass writes it
    double map_lod = 0.0;                 // the map's level, as the body pass samples it (BodyPass::map_lod)
    bool sky_first = false;               // written, not blended: the frame's sky is drawn first
    MoonOnAir moon;                       // the Moon's light on the air (a look-up from inside only)
    double disc_weight = 1.0;             // the planet's disc weight (passes/planet_light): the draw's times it
    int supersample = 1;                  // rays a pixel along each axis (a small disc seen from outside)
    glm::vec3 night_sky{0.0f};            // the night sky's own glow at the zenith, scene units (night_sky_glow)
    bool terrain = false;  // the planet is drawn as relief: every pixel with geometry marches up to it (the look-up)
};

// The night sky's own glow (shaders/shared/night_sky.glsl) over a camera at height_m above the
// ground, at the zenith, in scene units for a Sun of disc radiance sun_radiance: the snapshot's
// zenith luminance (cd/m^2) read against the physical Sun (atmosphere/solar_scale.hpp).
glm::vec3 night_sky_glow(float night_sky_cd_m2, double height_m, double sun_radiance);

class AtmospherePass : public RenderPass, public StarSkySource, public SkyInFrontSource {
public:
    using Atmospheres = std::map<uint16_t, std::unique_ptr<GpuAtmosphere>>;  // by body id

    // atmospheres: every body's that has one (not empty). halo: the glare's halo pass, when the
    // scene has one; the nearest atmosphere's draw adds its halo when it covers the whole channel.
    // bodies: the body pass whose maps a draw that relights a surface itself takes (draws_surface).
    AtmospherePass(Atmospheres atmospheres, const EclipseShadowUniforms& shadows, const GlareHaloPass* halo = nullptr,
                   const BodyPass* bodies = nullptr);

    // In the pass list: one draw per body with an atmosphere whose top-of-atmosphere sphere can
    // touch the frustum, far to near, each over everything drawn so far: reads the G-buffer,
    // blends into the colour.
    std::string name() const override { return "atmosphere"; }
    PassIo io() const override { return {.reads_geometry = true, .writes_color = true}; }
    int prepare(const FrameContext& frame) override;
    void draw(const PassInputs& in, int step) override;

    const Atmospheres& atmospheres() const { return atmospheres_; }
    long draws_run() const { return run_; }                   // summed over frames
    long draws_skipped() const { return skipped_; }           // atmosphere entirely outside the frustum
    long draws_marched() const { return marched_; }           // drawn by the per-pixel march
    long sky_view_renders() const;                            // sky-view tables rendered, all bodies (the Moon's too)
    long moonlit_draws() const { return moonlit_; }           // draws that added the Moon's light
    long halos_added() const { return halos_added_; }         // draws that added the glare's halo
    void set_add_halo(bool on) { add_halo_ = on; }            // SceneRenderer::set_halo_with_atmosphere
    long surfaces_drawn() const { return surfaces_drawn_; }   // draws that drew their planet's surface
    void set_draw_surfaces(bool on) { draw_surfaces_ = on; }  // SceneRenderer::set_surface_with_atmosphere
    // Whether this frame's draw of the planet's atmosphere draws its surface too, so the body pass
    // need not: the look-up, no other body in the air, no eclipse shadow on the planet, a map, and
    // the camera inside the air or, from outside, no other body that could be in front of the
    // air on screen. The ground's reflectance then comes from the map in the same draw
    // (shared/sphere_view.glsl, body_map_uv) instead of the G-buffer.
    bool draws_surface(const FrameContext& frame, const FrameBody& planet) const;
    // The G-buffer is read unless every planet with an atmosphere draws its own surface.
    bool reads_geometry_in(const FrameContext& frame) const override;
    // The sky behind the stars: the sky-view table of the atmosphere nearest the camera (by the
    // distance to its top), with the inputs this frame's draws give it. None when that atmosphere
    // has no table (a march level), when an eclipse shadow falls on its planet (the table has no
    // shadow: the stars of a total eclipse must not be judged against a sunlit sky), or without a Sun.
    StarSky star_sky(const FrameContext& frame) const override;
    // Whether this frame's sky is drawn first, before what lies beyond the air
    // (beyond_the_air.hpp): the only atmosphere in view draws its own surface from inside the air
    // (draws_surface), so its sky and ground together cover the channel, and there is a sky to
    // take the air in front from (star_sky). The same on every channel that sees that atmosphere
    // alone; a channel deciding otherwise draws the same image up to float rounding.
    bool sky_first(const FrameContext& frame) const;
    // The light a planet with air sends to the camera as a point (linear RGB, scene units x sr):
    // its disc's air and ground for a distant observer (GpuAtmosphere::disc_curve) over a ground of
    // reflectance ground_rgb, in the Sun's light at the planet. 0 for a body without air.
    glm::dvec3 point_flux(const FrameContext& frame, const FrameBody& planet, const glm::dvec3& ground_rgb) const;
    void set_sky_first(bool on) { sky_first_on_ = on; }  // SceneRenderer::set_sky_first
    // The air in front of what lies beyond it, after this frame's draw (sky_first): the layer's
    // table and its inputs, the halo if the draw added it.
    void set_sky_in_front(const GlProgram& p) const override;

    // One body's atmosphere. Blends into the bound framebuffer, within the shell's screen bounds.
    // geometry: the body pass's (reflectance, distance), distance < 0 where nothing was drawn.
    // geometry_in_air: another body meets the shell (its pixels are marched). extras: a glare halo
    // to add in the same draw (the look-up only; then it is marked composited), the surface to
    // draw (the look-up only: draws_surface must have said so).
    void draw(const ChannelView& view, GpuAtmosphere& atmosphere, const BodyState& state, const SphereView& sphere,
              const SunLight& sun, const GlTexture& geometry, const EclipseShadowUniforms& shadows,
              const shading::EclipseCasters& casters, bool geometry_in_air = true, AtmosphereDrawExtras extras = {});

private:
    struct Layer {
        const FrameBody* body;
        GpuAtmosphere* atmosphere;
        bool geometry_in_air;  // another body meets this atmosphere's shell, or the planet is relief
        bool terrain;          // the planet is drawn as relief (passes/terrain_drawer.hpp, draws_terrain)
        MoonOnAir moon;        // the Moon's light on its air this frame (atmosphere/moonlit_sky.hpp)
    };
    // The program for this draw: the look-up, or the march (set up with its own uniforms).
    // table_in: the sky-view table's (camera distance, Sun zenith cosine).
    // extras: added if the look-up is chosen (else cleared). half: 0 the whole draw, 1 its sky, 2
    // its ground with the planet's surface (extras.surface_map).
    const GlProgram& choose_program(GpuAtmosphere& atmosphere, const glm::vec2& table_in,
                                    const shading::EclipseCasters& casters, bool geometry_in_air,
                                    AtmosphereDrawExtras& extras, int half);
    // The Moon's table and light for a moonlit look-up (extras.moon.on).
    void set_moon_uniforms(const GlProgram& p, const ChannelView& view, GpuAtmosphere& atm, const SphereView& sphere,
                           const MoonOnAir& moon, double solar_scale);
    // What every draw of a layer sets: the view, the planet, the Sun, the tables, the G-buffer.
    void set_draw_uniforms(const GlProgram& p, const ChannelView& view, GpuAtmosphere& atm, const SphereView& sphere,
                           double solar_scale, const glm::dvec3& sun_dir, const GlTexture& geometry,
                           const EclipseShadowUniforms& shadows, const shading::EclipseCasters& casters);
    // Blends one draw over `cover` within the scissor r (dual-source: colour = add + colour * factor),
    // or writes it (replace: the sky drawn first, over a colour never cleared).
    void blend_draw(const GlProgram& p, const ChannelView& view, const PixelRect& r, const SphereView& cover,
                    bool replace = false);
    // The extras of layer `step`: its halo (halo_for) and surface (draws_surface).
    AtmosphereDrawExtras extras_for(int step) const;
    // The look-up program of a variant (bits: outside, geometry in the air, illustrative, glare
    // halo added, the ground half with the surface, the sky half, the sky drawn first, the surface
    // from its map seen from outside, the Moon's light, the planet drawn as relief), compiled on
    // first use.
    const GlProgram& lookup_program(int variant);
    // The glare halo the draw of layer `step` adds: the nearest layer's, when it covers the channel.
    const GlareHaloPass* halo_for(int step) const;
    Atmospheres atmospheres_;
    const EclipseShadowUniforms& shadows_;
    GlProgram program_;
    std::unique_ptr<GlProgram> lookup_programs_[1024];
    const GlareHaloPass* halo_;
    const BodyPass* bodies_;
    GlEmptyVertexArray vao_;
    const FrameContext* frame_ = nullptr;
    std::vector<Layer> layers_;  // this frame's draws
    long run_ = 0, skipped_ = 0, marched_ = 0, halos_added_ = 0, surfaces_drawn_ = 0, moonlit_ = 0;
    bool add_halo_ = true, draw_surfaces_ = true, sky_first_on_ = true;
};

}  // namespace cupola

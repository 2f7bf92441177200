#include "passes/atmosphere_pass.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "passes/atmosphere_uniforms.hpp"
#include "passes/sphere_screen_bounds.hpp"
#include "passes/terrain_drawer.hpp"

namespace cupola {

namespace {

GlTexture table_texture(const shading::Texture2DData& t, GLenum filter) {
    return GlTexture(t.width, t.height, t.texels.data(), filter);
}

// A table of the second wavelength triplet, or a 1x1 placeholder for a model with one triplet.
const shading::Texture2DData& second_table(const atmosphere::ProductionAtmosphere& m,
                                           shading::Texture2DData atmosphere::ProductionTables::*table) {
    static const shading::Texture2DData placeholder{1, 1, {glm::vec4(0.0f)}};
    return m.six_wavelengths() ? m.tables2().*table : placeholder;
}

atmosphere::ProductionAtmosphere make_model(const BodyConfig& body) {
    const AtmosphereConfig& c = body.atmosphere;
    if (std::abs(c.parameters.bottom_radius - body.radius_m) > 1e-6 * body.radius_m)
        throw std::runtime_error("body \"" + body.name + "\": the atmosphere's ground (" +
                                 std::to_string(c.parameters.bottom_radius) + " m) is not the body's radius (" +
                                 std::to_string(body.radius_m) + " m)");
    return atmosphere::ProductionAtmosphere(c.parameters, atmosphere::production_quality(c.model));
}

// tables: 2..5, sky view: 7..9
enum Unit : GLuint {
    kGeometry = 1,
    kTables = 2,
    kEclipseLut = 6,
    kSkyView = 7,
    kHalo = 10,
    kSurface = 11,
    kMoonSky = 12
};

// Direction from the planet's centre to the Sun (as the body pass lights it), and the Sun's
// irradiance there in scene units over that of the model's physical spectrum; in double.
// What the sky-view table depends on, from world positions in double (the same on every channel):
// the camera's distance from the centre and the Sun's zenith cosine at the camera, on the table's
// grid of Sun zenith angles (atmosphere::sky_view_table_sun_mu).
float camera_distance_m(const ChannelView& view, const BodyState& state) {
    return static_cast<float>(glm::length(view.camera_position_m - state.position_m));
}

glm::vec2 sky_view_inputs(const ChannelView& view, const BodyState& state, const glm::dvec3& sun_dir_world) {
    const glm::dvec3 up = view.camera_position_m - state.position_m;
    const double d = glm::length(up);
    const double mu_s = d > 0.0 ? glm::dot(up / d, sun_dir_world) : 1.0;
    return glm::vec2(static_cast<float>(d), atmosphere::sky_view_table_sun_mu(mu_s));
}

// Whether the eclipse shadows on a planet need the per-pixel march (the sky-view table has no
// shadow; the illustrative mode only tints the surface, which the look-up does itself).
bool shadow_needs_march(const shading::EclipseCasters& casters) {
    return casters.count > 0 && casters.mode != shading::ECLIPSE_MODE_ILLUSTRATIVE;
}

// Does a body other than the planet meet the sphere of its atmosphere's top (channel frame, double)?
bool other_body_in_shell(const FrameContext& frame, const FrameBody& planet, double top_radius_m) {
    const glm::dvec3 c = planet.sphere.center_dir * planet.sphere.distance_m;
    for (const FrameBody& b : frame.far_to_near) {
        if (&b == &planet || b.body->kind == BodyKind::Star) continue;
        const glm::dvec3 p = b.sphere.center_dir * b.sphere.distance_m;
        if (glm::length(p - c) < top_radius_m + b.body->radius_m) return true;
    }
    return false;
}
// Could a body other than the planet hide part of its atmosphere's shell from a camera outside it
// (channel frame, double)? Conservatively: any body not wholly beyond the shell's far side whose
// disc on screen overlaps the shell's. Without one, nothing is drawn in front of the air.
bool body_before_shell(const FrameContext& frame, const FrameBody& planet, double top_radius_m) {
    const double d = planet.sphere.distance_m;
    const double shell_rad = std::asin(std::min(top_radius_m / d, 1.0));
    for (const FrameBody& b : frame.far_to_near) {
        if (&b == &planet || b.sphere.distance_m - b.body->radius_m > d + top_radius_m) continue;
        const double b_rad = std::asin(std::min(b.body->radius_m / b.sphere.distance_m, 1.0));
        const double apart = std::acos(std::clamp(glm::dot(b.sphere.center_dir, planet.sphere.center_dir), -1.0, 1.0));
        if (apart < shell_rad + b_rad) return true;
    }
    return false;
}
}  // namespace

GpuAtmosphere::GpuAtmosphere(const BodyConfig& body)
    : model_(make_model(body)),
      transmittance_(table_texture(model_.tables().transmittance, GL_LINEAR)),
      multiple_scattering_(table_texture(model_.tables().multiple_scattering, GL_LINEAR)),
      irradiance_(table_texture(model_.tables().irradiance, GL_LINEAR)),
      color_weights_(table_texture(model_.color_weights(), GL_NEAREST)),
      transmittance2_(table_texture(second_table(model_, &atmosphere::ProductionTables::transmittance), GL_LINEAR)),
      multiple_scattering2_(
          table_texture(second_table(model_, &atmosphere::ProductionTables::multiple_scattering), GL_LINEAR)),
      irradiance2_(table_texture(second_table(model_, &atmosphere::ProductionTables::irradiance), GL_LINEAR)) {}

void GpuAtmosphere::bind_second(GLuint first_unit) const {
    transmittance2_.bind(first_unit);
    multiple_scattering2_.bind(first_unit + 1);
    irradiance2_.bind(first_unit + 2);
}

GpuSkyViewTable* GpuAtmosphere::sky_view() {
    if (!model_.quality().sky_view) return nullptr;
    if (!sky_view_) sky_view_ = std::make_unique<GpuSkyViewTable>(*this);
    return sky_view_.get();
}

GpuSkyViewTable* GpuAtmosphere::moon_sky_view() {
    if (!model_.quality().sky_view) return nullptr;
    if (!moon_sky_view_) moon_sky_view_ = std::make_unique<GpuSkyViewTable>(*this);
    return moon_sky_view_.get();
}

const atmosphere::AirDiscCurve& GpuAtmosphere::disc_curve() {
    if (!disc_curve_) disc_curve_ = std::make_unique<atmosphere::AirDiscCurve>(model_);
    return *disc_curve_;
}

void GpuAtmosphere::bind(GLuint first_unit) const {
    transmittance_.bind(first_unit);
    multiple_scattering_.bind(first_unit + 1);
    irradiance_.bind(first_unit + 2);
    color_weights_.bind(first_unit + 3);
}

bool sphere_outside_frustum(const ChannelFrustum& f, const glm::dvec3& c, double radius_m) {
    // Inward unit normals of the side planes from the (signed) half-angles: the left edge runs
    // along (-sin a, 0, -cos a), so its plane's inward normal is (cos a, 0, -sin a); likewise
    // for the others. Valid for any half-angle in (-90, 90) degrees.
    const double l = glm::radians(f.fov().left_deg), r = glm::radians(f.fov().right_deg);
    const double d = glm::radians(f.fov().down_deg), u = glm::radians(f.fov().up_deg);
    const glm::dvec3 normals[4] = {{std::cos(l), 0.0, -std::sin(l)},
                                   {-std::cos(r), 0.0, -std::sin(r)},
                                   {0.0, std::cos(d), -std::sin(d)},
                                   {0.0, -std::cos(u), -std::sin(u)}};
    for (const glm::dvec3& n : normals)
        if (glm::dot(n, c) < -radius_m) return true;
    return false;
}

AtmospherePass::AtmospherePass(Atmospheres atmospheres, const EclipseShadowUniforms& shadows, const GlareHaloPass* halo,
                               const BodyPass* bodies)
    : atmospheres_(std::move(atmospheres)),
      shadows_(shadows),
      program_("sphere.vert", "atmosphere.frag"),
      halo_(halo),
      bodies_(bodies) {}

const GlProgram& AtmospherePass::lookup_program(int variant) {
    auto& p = lookup_programs_[variant & 1023];
    if (!p) {
        const std::string defines =
            "#define SKY_OUTSIDE " + std::to_string(variant & 1) + "\n#define SKY_GEOMETRY " +
            std::to_string((variant >> 1) & 1) + "\n#define SKY_ILLUSTRATIVE " + std::to_string((variant >> 2) & 1) +
            "\n#define SKY_HALO " + std::to_string((variant >> 3) & 1) + "\n#define SKY_HALF " +
            std::to_string((variant & 16)   ? 2
                           : (variant & 32) ? 1
                                            : 0) +
            "\n#define SKY_FIRST " + std::to_string((variant >> 6) & 1) + "\n#define SKY_MAP " +
            std::to_string((variant >> 7) & 1) + "\n#define SKY_MOON " + std::to_string((variant >> 8) & 1) +
            "\n#define SKY_TERRAIN " + std::to_string((variant >> 9) & 1) + "\n";
        p = std::make_unique<GlProgram>("sphere.vert", "atmosphere_lookup.frag", defines);
    }
    return *p;
}

long AtmospherePass::sky_view_renders() const {
    long n = 0;
    for (const auto& it : atmospheres_)
        for (const GpuSkyViewTable* t : {it.second->sky_view_if_made(), it.second->moon_sky_view_if_made()})
            if (t) n += t->renders();
    return n;
}

int AtmospherePass::prepare(const FrameContext& frame) {
    frame_ = &frame;
    layers_.clear();
    long skipped = 0;
    for (const FrameBody& it : frame.far_to_near) {
        const auto atm = atmospheres_.find(it.body->id);
        if (atm == atmospheres_.end()) continue;
        const glm::dvec3 center = it.sphere.center_dir * it.sphere.distance_m;  // channel frame, double
        if (it.light.disc_weight <= 0.0 ||  // a point only (PlanetPointPass): no air drawn
            sphere_outside_frustum(*frame.view.frustum, center, atm->second->top_radius_m())) {
            ++skipped;
            continue;
        }
        const PlanetSun ps = planet_sun(*it.state, frame.light, &atm->second->model());
        const bool relief = draws_terrain(frame, it);
        layers_.push_back({&it, atm->second.get(),
                           relief || other_body_in_shell(frame, it, atm->second->top_radius_m()), relief,
                           moon_on_air(frame.moonlight, frame.view.camera_position_m, it.state->position_m,
                                       ps.dir_world, ps.irradiance, atm->second->model())});
    }
    run_ += static_cast<long>(layers_.size());
    skipped_ += skipped;
    spdlog::debug("frame {}: atmosphere passes {} run, {} skipped (totals {} / {})", frame.snap->frame, layers_.size(),
                  skipped, run_, skipped_);
    return static_cast<int>(layers_.size());
}

const GlareHaloPass* AtmospherePass::halo_for(int step) const {
    if (!halo_ || !add_halo_ || step + 1 != static_cast<int>(layers_.size()) || !halo_->has_halo()) return nullptr;
    // The camera inside the shell: its draw covers the viewport (make_sphere_view's rule).
    const Layer& l = layers_.back();
    return l.body->sphere.distance_m <= l.atmosphere->top_radius_m() ? halo_ : nullptr;
}

bool AtmospherePass::draws_surface(const FrameContext& f, const FrameBody& planet) const {
    if (!draw_surfaces_ || !bodies_ || !bodies_->texture(planet.body->id)) return false;
    if (draws_terrain(f, planet)) return false;  // the painter draws its relief
    const auto a = atmospheres_.find(planet.body->id);
    if (a == atmospheres_.end() || !a->second->model().quality().sky_view) return false;
    if (f.casters_of(planet.body->id).count > 0) return false;  // shadows: the march, or the tint
    const double top_m = a->second->top_radius_m();
    if (other_body_in_shell(f, planet, top_m)) return false;
    const float d = camera_distance_m(f.view, *planet.state);  // as the table's input
    return !shading::atm_camera_outside(a->second->model().shader_params(), d) || !body_before_shell(f, planet, top_m);
}

bool AtmospherePass::reads_geometry_in(const FrameContext& f) const {
    for (const FrameBody& b : f.far_to_near)
        if (atmospheres_.count(b.body->id) && !draws_surface(f, b)) return true;
    return false;
}

StarSky AtmospherePass::star_sky(const FrameContext& f) const {
    StarSky out;
    const FrameBody* planet = nullptr;
    GpuAtmosphere* atm = nullptr;
    double nearest = std::numeric_limits<double>::infinity();
    for (const FrameBody& b : f.far_to_near) {
        const auto it = atmospheres_.find(b.body->id);
        if (it == atmospheres_.end()) continue;
        const double gap = b.sphere.distance_m - it->second->top_radius_m();
        if (gap < nearest) {
            nearest = gap;
            planet = &b;
            atm = it->second.get();
        }
    }
    if (!planet || !(f.light.radiance > 0.0)) return out;
    if (shadow_needs_march(f.casters_of(planet->body->id))) return out;
    const PlanetSun ps = planet_sun(*planet->state, f.light, &atm->model());
    GpuSkyViewTable* table = atm->sky_view();
    if (!table || !(ps.solar_scale > 0.0)) return out;
    const glm::dvec3 to_centre = planet->state->position_m - f.view.camera_position_m;
    out.table = table;
    out.table_in = sky_view_inputs(f.view, *planet->state, ps.dir_world);
    out.params = atm->model().shader_params();
    out.center_dir_world = glm::vec3(glm::normalize(to_centre));
    out.sun_world = glm::vec3(ps.dir_world);
    out.to_cd_m2 = static_cast<float>(atmosphere::sky_to_cd_m2(ps.solar_scale, f.light.radiance));
    if (f.snap)
        out.night_sky_cd_m2 =
            shading::night_sky_at_height(f.snap->settings.night_sky_cd_m2,
                                         static_cast<float>(planet->sphere.distance_m - out.params.bottom_radius_m));
    const MoonOnAir moon = moon_on_air(f.moonlight, f.view.camera_position_m, planet->state->position_m, ps.dir_world,
                                       ps.irradiance, atm->model());
    if (moon.on) {  // the same rule as the atmosphere's draw
        out.moon_table = atm->moon_sky_view();
        out.moon_mu = moon.mu;
        out.moon_world = glm::vec3(moon.dir_world);
        out.moon_ratio = static_cast<float>(shading::rec709_luminance(glm::vec3(moon.ratio_rgb)));
    }
    return out;
}

glm::dvec3 AtmospherePass::point_flux(const FrameContext& f, const FrameBody& planet,
                                      const glm::dvec3& ground_rgb) const {
    const auto a = atmospheres_.find(planet.body->id);
    if (a == atmospheres_.end()) return glm::dvec3(0.0);
    const PlanetSun ps = planet_sun(*planet.state, f.light, &a->second->model());
    const glm::dvec3 to_camera = f.view.camera_position_m - planet.state->position_m;
    const double d = glm::length(to_camera);
    if (!(ps.solar_scale > 0.0) || d <= a->second->top_radius_m()) return glm::dvec3(0.0);
    const double phase_deg = glm::degrees(std::acos(std::clamp(glm::dot(to_camera / d, ps.dir_world), -1.0, 1.0)));
    return glm::max(a->second->disc_curve().flux_rgb(phase_deg, ground_rgb, d), glm::dvec3(0.0)) * ps.solar_scale;
}

bool AtmospherePass::sky_first(const FrameContext& f) const {
    if (!sky_first_on_) return false;
    const FrameBody* only = nullptr;  // the only atmosphere in view (prepare's rule)
    for (const FrameBody& b : f.far_to_near) {
        const auto a = atmospheres_.find(b.body->id);
        if (a == atmospheres_.end() ||
            sphere_outside_frustum(*f.view.frustum, b.sphere.center_dir * b.sphere.distance_m,
                                   a->second->top_radius_m()))
            continue;
        if (only) return false;
        only = &b;
    }
    if (!only || !draws_surface(f, *only) || !star_sky(f).table) return false;
    // From inside the air, where its sky and its ground cover every pixel.
    const auto a = atmospheres_.find(only->body->id);
    return !shading::atm_camera_outside(a->second->model().shader_params(), camera_distance_m(f.view, *only->state));
}

void AtmospherePass::set_sky_in_front(const GlProgram& p) const {
    if (!frame_ || !frame_->sky_first || layers_.size() != 1)
        throw std::logic_error("atmosphere pass: no sky was drawn first this frame to take the air in front from");
    const Layer& l = layers_.front();
    const FrameContext& f = *frame_;
    const shading::AtmosphereParams& a = l.atmosphere->model().shader_params();
    const PlanetSun ps = planet_sun(*l.body->state, f.light, &l.atmosphere->model());
    const glm::vec2 table_in = sky_view_inputs(f.view, *l.body->state, ps.dir_world);
    // As the draw had them (set_draw_uniforms, shade() in atmosphere_lookup.frag).
    const glm::vec3 up = -glm::vec3(l.body->sphere.center_dir), sun(f.view.world_to_channel * ps.dir_world);
    GpuSkyViewTable& table = *l.atmosphere->sky_view();
    set_atmosphere_params(p, a);
    p.set("u_sky.up", up);
    p.set("u_sky.r_m", std::max(static_cast<float>(l.body->sphere.distance_m), a.bottom_radius_m + 1.0f));
    p.set("u_sky.mu_h", shading::atm_sky_view_horizon_mu(a, table_in.x));
    p.set("u_sky.sun", sun);
    p.set("u_sky.sun_perp", shading::atm_sky_view_sun_perp(up, sun));
    p.set("u_sky.size", table.size());
    p.set("u_sky.solar_scale", static_cast<float>(ps.solar_scale));
    const glm::vec3 moon(f.view.world_to_channel * l.moon.dir_world);
    p.set("u_sky.moon", moon);
    p.set("u_sky.moon_perp", shading::atm_sky_view_sun_perp(up, moon));
    p.set("u_sky.moon_scale", l.moon.on ? glm::vec3(l.moon.ratio_rgb * ps.solar_scale) : glm::vec3(0.0f));
    if (l.moon.on) {  // the table the sky's draw brought up to date
        l.atmosphere->moon_sky_view()->bind(kFirstUnit + 4);
        p.set("u_sky_moon_phased", static_cast<int>(kFirstUnit + 4));
        p.set("u_sky_moon_mie", static_cast<int>(kFirstUnit + 5));
    }
    table.bind(kFirstUnit);
    p.set("u_sky_phased", static_cast<int>(kFirstUnit));
    p.set("u_sky_mie", static_cast<int>(kFirstUnit + 1));
    p.set("u_sky_third", static_cast<int>(kFirstUnit + 2));
    const bool halo = halo_ && halo_->composited();
    p.set("u_halo_on", halo ? 1 : 0);
    if (!halo) return;
    halo_->texture().bind(kFirstUnit + 3);
    p.set("u_halo", static_cast<int>(kFirstUnit + 3));
    p.set("u_halo_map", halo_->grid().map);
}

glm::vec3 night_sky_glow(float night_sky_cd_m2, double height_m, double sun_radiance) {
    const double at_height = shading::night_sky_at_height(1.0f, static_cast<float>(height_m));
    return shading::night_sky_rgb(night_sky_cd_m2) *
           static_cast<float>(at_height * sun_radiance / atmosphere::kPhysicalSunRadiance_cd_m2);
}

AtmosphereDrawExtras AtmospherePass::extras_for(int step) const {
    AtmosphereDrawExtras e;
    e.halo = halo_for(step);
    const Layer& l = layers_.at(static_cast<size_t>(step));
    e.moon = l.moon;
    e.disc_weight = l.body->light.disc_weight;
    e.supersample = l.body->light.supersample;
    e.terrain = l.terrain;
    if (frame_->snap)
        e.night_sky = night_sky_glow(frame_->snap->settings.night_sky_cd_m2,
                                     l.body->sphere.distance_m - l.atmosphere->model().shader_params().bottom_radius_m,
                                     frame_->light.radiance);
    if (draws_surface(*frame_, *l.body)) {
        e.surface_map = bodies_->texture(l.body->body->id);
        e.map_lod = BodyPass::map_lod(frame_->view, l.body->sphere, *l.body->body, e.surface_map->width());
        e.channel_to_body = BodyPass::channel_to_body(frame_->view, *l.body->state);
        e.surface_reflectance = glm::vec3(l.body->body->tint) * static_cast<float>(l.body->body->albedo);
        e.sky_first = frame_->sky_first;
    } else if (frame_->sky_first) {
        throw std::logic_error("atmosphere pass: the sky is drawn first but does not draw its ground");
    }
    return e;
}

void AtmospherePass::draw(const PassInputs& in, int step) {
    const Layer& l = layers_.at(static_cast<size_t>(step));
    const FrameContext& f = *frame_;
    draw(f.view, *l.atmosphere, *l.body->state, l.body->sphere, f.light, *in.geometry, shadows_,
         f.casters_of(l.body->body->id), l.geometry_in_air, extras_for(step));
}

const GlProgram& AtmospherePass::choose_program(GpuAtmosphere& atm, const glm::vec2& table_in,
                                                const shading::EclipseCasters& casters, bool geometry_in_air,
                                                AtmosphereDrawExtras& extras, int half) {
    const atmosphere::ProductionAtmosphere& m = atm.model();
    const bool shadowed = shadow_needs_march(casters);
    GpuSkyViewTable* table = atm.sky_view();
    if (table && !shadowed) {
        table->update(table_in.x, table_in.y);
        const shading::AtmosphereParams& a = m.shader_params();
        const bool outside = shading::atm_camera_outside(a, table_in.x);
        const bool illustrative = casters.count > 0;
        if (outside) extras.moon.on = false;  // atmosphere/moonlit_sky.hpp: from inside the air only
        if (extras.moon.on) atm.moon_sky_view()->update(table_in.x, extras.moon.mu);  // before the program is used
        const GlProgram& lookup = lookup_program(
            (outside ? 1 : 0) | (geometry_in_air ? 2 : 0) | (illustrative ? 4 : 0) | (extras.halo ? 8 : 0) |
            (half == 2   ? 16
             : half == 1 ? 32
                         : 0) |
            (extras.sky_first ? 64 : 0) | (extras.surface_map && outside ? 128 : 0) | (extras.moon.on ? 256 : 0) |
            (extras.terrain ? 512 : 0));
        lookup.use();
        if (extras.halo) {
            extras.halo->texture().bind(kHalo);
            lookup.set("u_halo", static_cast<int>(kHalo));
            lookup.set("u_halo_map", extras.halo->grid().map);
        }
        if (extras.surface_map) {
            extras.surface_map->bind(kSurface);
            lookup.set("u_body_map", static_cast<int>(kSurface));
            lookup.set("u_channel_to_body", extras.channel_to_body);
            lookup.set("u_reflectance", extras.surface_reflectance);
            lookup.set("u_map_lod", static_cast<float>(extras.map_lod));
        }
        table->bind(kSkyView);
        lookup.set("u_sky_phased", static_cast<int>(kSkyView));
        lookup.set("u_sky_mie", static_cast<int>(kSkyView + 1));
        lookup.set("u_sky_third", static_cast<int>(kSkyView + 2));
        lookup.set("u_sky_size", table->size());
        lookup.set("u_mu_h", shading::atm_sky_view_horizon_mu(a, table_in.x));
        lookup.set("u_samples", m.quality().view_samples);
        return lookup;
    }
    ++marched_;
    if (extras.surface_map) throw std::logic_error("atmosphere pass: a marched draw cannot draw the planet's surface");
    extras.halo = nullptr;   // the march adds none: the glare pass upsamples it
    extras.moon.on = false;  // nor the Moon's light (the look-up's alone)
    const atmosphere::ProductionQuality& q = m.quality();
    program_.use();
    program_.set("u_fit.k1_rad", m.analytic_fit().k1_rad);
    program_.set("u_fit.k2", m.analytic_fit().k2);
    program_.set("u_analytic", q.analytic ? 1 : 0);
    program_.set("u_use_ms", q.multiple_scattering ? 1 : 0);
    program_.set("u_samples", q.view_samples);
    return program_;
}

void AtmospherePass::draw(const ChannelView& view, GpuAtmosphere& atm, const BodyState& state, const SphereView& sphere,
                          const SunLight& sun, const GlTexture& geometry, const EclipseShadowUniforms& shadows,
                          const shading::EclipseCasters& casters, bool geometry_in_air, AtmosphereDrawExtras extras) {
    const atmosphere::ProductionAtmosphere& m = atm.model();
    const PlanetSun ps = planet_sun(state, sun, &m);
    const glm::vec2 table_in = sky_view_inputs(view, state, ps.dir_world);
    const glm::dvec3 sun_dir = view.world_to_channel * ps.dir_world;
    const PixelRect r = sphere_screen_bounds(*view.frustum, sphere.center_dir * sphere.distance_m, atm.top_radius_m());
    const auto set_uniforms = [&](const GlProgram& p) {
        set_draw_uniforms(p, view, atm, sphere, ps.solar_scale, sun_dir, geometry, shadows, casters);
        if (extras.moon.on) set_moon_uniforms(p, view, atm, sphere, extras.moon, ps.solar_scale);
        p.set("u_disc_weight", static_cast<float>(extras.disc_weight));
        p.set("u_supersample", extras.supersample);
        p.set("u_night_sky", extras.night_sky);
    };
    if (!extras.surface_map || shading::atm_camera_outside(m.shader_params(), table_in.x)) {
        // Only the pixels that can see the top of the atmosphere: its cap seen from outside (a
        // fan), the viewport from inside; the scissor bounds both. From outside, with the surface
        // drawn here, the planet's map gives its reflectance (SKY_MAP).
        const GlProgram& p = choose_program(atm, table_in, casters, geometry_in_air, extras, 0);
        set_uniforms(p);
        blend_draw(p, view, r, make_sphere_view(view, state.position_m, atm.top_radius_m()));
    } else {
        // Two draws split by the ray's ground flag, each discarding the other's pixels: the sky over
        // the cap around the zenith that misses the planet, the ground (with the planet's map) over
        // the planet's own cap.
        const GlProgram& sky = choose_program(atm, table_in, casters, geometry_in_air, extras, 1);
        set_uniforms(sky);
        blend_draw(sky, view, r, complement_cover(view, sphere), extras.sky_first);
        const GlProgram& ground = choose_program(atm, table_in, casters, geometry_in_air, extras, 2);
        set_uniforms(ground);
        blend_draw(ground, view, r, sphere, extras.sky_first);
    }
    if (extras.halo) {
        extras.halo->mark_composited();
        ++halos_added_;
    }
    if (extras.surface_map) ++surfaces_drawn_;
    if (extras.moon.on) ++moonlit_;
    gl::check("atmosphere pass (" + m.parameters().name + ")");
}

void AtmospherePass::set_moon_uniforms(const GlProgram& p, const ChannelView& view, GpuAtmosphere& atm,
                                       const SphereView& sphere, const MoonOnAir& moon, double solar_scale) {
    const glm::vec3 moon_dir(view.world_to_channel * moon.dir_world);
    atm.moon_sky_view()->bind(kMoonSky);
    p.set("u_moon_phased", static_cast<int>(kMoonSky));
    p.set("u_moon_mie", static_cast<int>(kMoonSky + 1));
    p.set("u_moon_third", static_cast<int>(kMoonSky + 2));
    p.set("u_moon", moon_dir);
    p.set("u_moon_perp", shading::atm_sky_view_sun_perp(-glm::vec3(sphere.center_dir), moon_dir));
    p.set("u_moon_scale", glm::vec3(moon.ratio_rgb * solar_scale));
}

void AtmospherePass::set_draw_uniforms(const GlProgram& p, const ChannelView& view, GpuAtmosphere& atm,
                                       const SphereView& sphere, double solar_scale, const glm::dvec3& sun_dir,
                                       const GlTexture& geometry, const EclipseShadowUniforms& shadows,
                                       const shading::EclipseCasters& casters) {
    const atmosphere::ProductionAtmosphere& m = atm.model();
    p.set("u_tangents", view.tangents());
    p.set("u_size", view.size());
    p.set("u_center_dir", glm::vec3(sphere.center_dir));
    p.set("u_sin_alpha", static_cast<float>(std::min(sphere.sin_alpha, 1.0)));
    p.set("u_distances_m", sphere_distances(sphere));
    p.set("u_d_m", static_cast<float>(sphere.distance_m));
    p.set("u_sun", glm::vec3(sun_dir));
    p.set("u_sun_perp", shading::atm_sky_view_sun_perp(-glm::vec3(sphere.center_dir), glm::vec3(sun_dir)));
    p.set("u_solar_scale", static_cast<float>(solar_scale));
    set_atmosphere_params(p, m.shader_params());
    bind_atmosphere_tables(p, atm, kTables);
    p.set("u_geometry", static_cast<int>(kGeometry));
    geometry.bind(kGeometry);
    shadows.apply(p, casters, kEclipseLut);
}

void AtmospherePass::blend_draw(const GlProgram& p, const ChannelView& view, const PixelRect& r,
                                const SphereView& cover, bool replace) {
    if (r.empty()) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(r.x, r.y, r.width, r.height);
    if (replace)
        glDisablei(GL_BLEND, 0);
    else
        glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_ONE, GL_SRC1_COLOR, GL_ONE, GL_SRC1_ALPHA);
    vao_.bind();
    draw_cover(p, view, cover);
    glDisablei(GL_BLEND, 0);
    glDisable(GL_SCISSOR_TEST);
}

}  // namespace cupola

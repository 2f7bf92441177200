#include "passes/atmosphere_pass.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>

#include "atmosphere/solar_scale.hpp"

namespace cupola {

namespace {

GlTexture table_texture(const shading::Texture2DData& t, GLenum filter) {
    return GlTexture(t.width, t.height, t.texels.data(), filter);
}

atmosphere::ProductionAtmosphere make_model(const BodyConfig& body) {
    const AtmosphereConfig& c = body.atmosphere;
    if (std::abs(c.parameters.bottom_radius - body.radius_m) > 1e-6 * body.radius_m)
        throw std::runtime_error("body \"" + body.name + "\": the atmosphere's ground (" +
                                 std::to_string(c.parameters.bottom_radius) + " m) is not the body's radius (" +
                                 std::to_string(body.radius_m) + " m)");
    return atmosphere::ProductionAtmosphere(c.parameters, atmosphere::production_quality(c.model));
}

glm::vec2 size_of(const shading::Texture2DData& t) { return glm::vec2(t.width, t.height); }

// The AtmosphereParams uniform struct, member by member.
void set_params(const GlProgram& p, const shading::AtmosphereParams& a) {
    p.set("u_atm.bottom_radius_m", a.bottom_radius_m);
    p.set("u_atm.top_radius_m", a.top_radius_m);
    p.set("u_atm.rayleigh_scattering_per_m", a.rayleigh_scattering_per_m);
    p.set("u_atm.rayleigh_scale_height_m", a.rayleigh_scale_height_m);
    p.set("u_atm.mie_scattering_per_m", a.mie_scattering_per_m);
    p.set("u_atm.mie_extinction_per_m", a.mie_extinction_per_m);
    p.set("u_atm.mie_scale_height_m", a.mie_scale_height_m);
    p.set("u_atm.mie_g", a.mie_g);
    p.set("u_atm.ozone_absorption_per_m", a.ozone_absorption_per_m);
    p.set("u_atm.ozone_bottom_m", a.ozone_bottom_m);
    p.set("u_atm.ozone_peak_m", a.ozone_peak_m);
    p.set("u_atm.ozone_top_m", a.ozone_top_m);
    p.set("u_atm.ground_albedo", a.ground_albedo);
}

enum Unit : GLuint { kScene = 0, kGeometry = 1, kTables = 2, kEclipseLut = 6 };  // tables: 2..5

}  // namespace

GpuAtmosphere::GpuAtmosphere(const BodyConfig& body)
    : model_(make_model(body)),
      transmittance_(table_texture(model_.tables().transmittance, GL_LINEAR)),
      multiple_scattering_(table_texture(model_.tables().multiple_scattering, GL_LINEAR)),
      irradiance_(table_texture(model_.tables().irradiance, GL_LINEAR)),
      color_weights_(table_texture(model_.color_weights(), GL_NEAREST)) {}

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

AtmospherePass::AtmospherePass(Atmospheres atmospheres, const EclipseShadowUniforms& shadows)
    : atmospheres_(std::move(atmospheres)), shadows_(shadows), program_("fullscreen.vert", "atmosphere.frag") {}

int AtmospherePass::prepare(const FrameContext& frame) {
    frame_ = &frame;
    layers_.clear();
    long skipped = 0;
    for (const FrameBody& it : frame.far_to_near) {
        const auto atm = atmospheres_.find(it.body->id);
        if (atm == atmospheres_.end()) continue;
        const glm::dvec3 center = it.sphere.center_dir * it.sphere.distance_m;  // channel frame, double
        if (sphere_outside_frustum(*frame.view.frustum, center, atm->second->top_radius_m())) {
            ++skipped;
            continue;
        }
        layers_.push_back({&it, atm->second.get()});
    }
    run_ += static_cast<long>(layers_.size());
    skipped_ += skipped;
    spdlog::debug("frame {}: atmosphere passes {} run, {} skipped (totals {} / {})", frame.snap->frame, layers_.size(),
                  skipped, run_, skipped_);
    return static_cast<int>(layers_.size());
}

void AtmospherePass::draw(const PassInputs& in, int step) {
    const Layer& l = layers_.at(static_cast<size_t>(step));
    const FrameContext& f = *frame_;
    draw(f.view, *l.atmosphere, *l.body->state, l.body->sphere, f.light, *in.color, *in.geometry, shadows_,
         f.casters_of(l.body->body->id));
}

void AtmospherePass::draw(const ChannelView& view, const GpuAtmosphere& atm, const BodyState& state,
                          const SphereView& sphere, const SunLight& sun, const GlTexture& scene,
                          const GlTexture& geometry, const EclipseShadowUniforms& shadows,
                          const shading::EclipseCasters& casters) {
    const atmosphere::ProductionAtmosphere& m = atm.model();
    const atmosphere::ProductionQuality& q = m.quality();
    // Direction to the Sun from the planet's centre (as the body pass lights it), and the
    // Sun's irradiance there in scene units; all in double.
    glm::dvec3 sun_dir = -sphere.center_dir;  // no Sun: any unit vector (solar_scale is 0)
    double solar_scale = 0.0;
    if (sun.present) {
        const glm::dvec3 to_sun = sun.position_m - state.position_m;
        const double d_sun = glm::length(to_sun);
        if (d_sun > 0.0) {
            sun_dir = view.world_to_channel * (to_sun / d_sun);
            solar_scale = sun_irradiance(sun, d_sun) / atmosphere::physical_solar_illuminance(m);
        }
    }

    program_.use();
    program_.set("u_tangents", view.tangents());
    program_.set("u_size", view.size());
    program_.set("u_center_dir", glm::vec3(sphere.center_dir));
    program_.set("u_sin_alpha", static_cast<float>(std::min(sphere.sin_alpha, 1.0)));
    program_.set("u_distances_m", sphere_distances(sphere));
    program_.set("u_d_m", static_cast<float>(sphere.distance_m));
    program_.set("u_sun", glm::vec3(sun_dir));
    program_.set("u_solar_scale", static_cast<float>(solar_scale));
    set_params(program_, m.shader_params());
    program_.set("u_fit.k1_rad", m.analytic_fit().k1_rad);
    program_.set("u_fit.k2", m.analytic_fit().k2);
    program_.set("u_analytic", q.analytic ? 1 : 0);
    program_.set("u_use_ms", q.multiple_scattering ? 1 : 0);
    program_.set("u_samples", q.view_samples);
    program_.set("u_trans_size", size_of(m.tables().transmittance));
    program_.set("u_ms_size", size_of(m.tables().multiple_scattering));
    program_.set("u_irr_size", size_of(m.tables().irradiance));
    program_.set("u_weight_count", static_cast<float>(m.color_weights().width));
    program_.set("u_scene", static_cast<int>(kScene));
    program_.set("u_geometry", static_cast<int>(kGeometry));
    program_.set("u_transmittance", static_cast<int>(kTables));
    program_.set("u_multiple_scattering", static_cast<int>(kTables + 1));
    program_.set("u_irradiance", static_cast<int>(kTables + 2));
    program_.set("u_weights", static_cast<int>(kTables + 3));
    scene.bind(kScene);
    geometry.bind(kGeometry);
    atm.bind(kTables);
    shadows.apply(program_, casters, kEclipseLut);
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gl::check("atmosphere pass (" + m.parameters().name + ")");
}

}  // namespace cupola

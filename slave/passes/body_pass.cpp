#include "passes/body_pass.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <utility>

#include "atmosphere/solar_scale.hpp"
#include "passes/body_map.hpp"

namespace cupola {

double sun_irradiance(const SunLight& sun, double d_m) {
    if (!sun.present || d_m <= 0.0) return 0.0;
    return atmosphere::sun_irradiance_scene_units(sun.radiance, sun.radius_m, sun.limb_u, d_m);
}

namespace {
constexpr unsigned kOblate = 1, kAfterSky = 2, kShadowed = 4, kRings = 8;

std::string body_defines(unsigned variant) {
    auto flag = [&](const char* name, unsigned bit) {
        return std::string("#define ") + name + ((variant & bit) ? " 1\n" : " 0\n");
    };
    return flag("BODY_ECLIPSE", kShadowed) + flag("BODY_AFTER_SKY", kAfterSky) + flag("BODY_OBLATE", kOblate) +
           flag("BODY_RINGS", kRings);
}

// Every variant a body of the scene can need: shadowed or not, drawn after the sky or not, oblate
// for a flattened body, with its rings' shadow for a ringed planet.
std::set<unsigned> variants_needed(const SceneConfig& scene) {
    std::set<unsigned> out;
    for (const auto& b : scene.bodies) {
        if (b.kind == BodyKind::Star) continue;
        const unsigned shape = (b.flattening > 0.0 ? kOblate : 0u) | (b.rings.present ? kRings : 0u);
        for (const unsigned v : {0u, kAfterSky, kShadowed, kAfterSky | kShadowed}) out.insert(shape | v);
    }
    return out;
}
}  // namespace

BodyPass::BodyPass(const SceneConfig& scene) : rings_(scene) {
    for (const unsigned v : variants_needed(scene))
        programs_[v] = std::make_unique<GlProgram>("sphere.vert", "body.frag", body_defines(v));
    for (const auto& b : scene.bodies) {
        if (b.kind == BodyKind::Star) continue;
        BodyMap map = take_body_map(b.texture, glm::dvec3(b.tint));
        textures_[b.id] = std::make_unique<GlTexture>(map.image.width, map.image.height, map.image.rgb, map.mips);
        map_means_[b.id] = map.mean_rgb;
        map_grids_[b.id] = std::move(map.grid);
    }
}

const LuminanceGrid* BodyPass::map_grid(uint16_t body_id) const {
    const auto g = map_grids_.find(body_id);
    return g == map_grids_.end() ? nullptr : &g->second;
}

glm::dvec3 BodyPass::map_mean_rgb(uint16_t body_id) const {
    const auto m = map_means_.find(body_id);
    return m == map_means_.end() ? glm::dvec3(0.0) : m->second;
}

const GlProgram& BodyPass::program(bool oblate, bool after_sky, bool shadowed, bool rings) const {
    const unsigned v =
        (oblate ? kOblate : 0u) | (after_sky ? kAfterSky : 0u) | (shadowed ? kShadowed : 0u) | (rings ? kRings : 0u);
    return *programs_.at(v);
}

SphereView BodyPass::oblate_sphere(const GlProgram& program, const ChannelView& view, const BodyConfig& body,
                                   const BodyState& state, const SphereView& sphere) {
    // u_to_sphere = B^T diag(1, 1, 1 / (1 - f)) B, B = channel -> body, all in double; its inverse.
    const glm::dmat3 to_sphere = channel_to_stretched(view, body, state), from_sphere = glm::inverse(to_sphere);
    program.set("u_to_sphere", glm::mat3(to_sphere));
    program.set("u_from_sphere", glm::mat3(from_sphere));
    SphereView s = sphere;
    const glm::dvec3 centre = to_sphere * (sphere.center_dir * sphere.distance_m);
    s.distance_m = glm::length(centre);
    if (s.distance_m > 0.0) {
        s.center_dir = centre / s.distance_m;
        s.sin_alpha = sphere.radius_m / s.distance_m;
    }
    return s;
}

const GlTexture* BodyPass::texture(uint16_t body_id) const {
    const auto t = textures_.find(body_id);
    return t == textures_.end() ? nullptr : t->second.get();
}

glm::mat3 BodyPass::channel_to_body(const ChannelView& view, const BodyState& state) {
    return glm::mat3(glm::transpose(glm::mat3_cast(state.orientation)) * view.channel_to_world);
}

double BodyPass::map_lod(const ChannelView& view, const SphereView& sphere, const BodyConfig& body, int map_width) {
    const double pixel_on_body_rad = pixel_angle_rad(*view.frustum) * sphere.distance_m / body.radius_m;
    const double texels = pixel_on_body_rad * map_width / (2.0 * std::numbers::pi);
    return std::max(0.0, std::log2(std::max(texels, 1e-30)));
}

void BodyPass::draw(const ChannelView& view, const BodyConfig& body, const BodyState& state, const SphereView& sphere,
                    const SunLight& sun, const EclipseShadowUniforms& shadows, const shading::EclipseCasters& casters,
                    const SkyInFrontSource* sky, const PlanetLight& light) {
    const auto tex = textures_.find(body.id);
    if (tex == textures_.end()) return;
    const glm::dvec3 to_sun = sun.position_m - state.position_m;  // double, world frame
    const double d_sun = glm::length(to_sun);
    const glm::dvec3 sun_dir = d_sun > 0.0 ? view.world_to_channel * (to_sun / d_sun) : glm::dvec3(0.0);
    const double light_scale = light.disc_scale * light.disc_weight;
    const double lit = light_scale * body.albedo / std::numbers::pi * sun_irradiance(sun, d_sun);

    const bool shadowed = casters.count > 0 && !body.atmosphere.present, oblate = body.flattening > 0.0;
    const bool rings = rings_.has_rings(body.id);
    const GlProgram& program = this->program(oblate, sky != nullptr, shadowed, rings);
    program.use();
    if (rings) rings_.set_shadow_uniforms(program, view, body, state);
    program.set("u_channel_to_body", channel_to_body(view, state));
    program.set("u_sun_dir", glm::vec3(sun_dir));
    program.set("u_lit", glm::vec3(body.tint) * static_cast<float>(lit));
    program.set("u_reflectance", glm::vec3(body.tint) * static_cast<float>(body.albedo));
    program.set("u_texture", 0);
    program.set("u_limb_aa", light.small_disc ? 1 : 0);
    program.set("u_limb_weight", static_cast<float>(light.limb_weight));
    program.set("u_shine_dir", glm::vec3(view.world_to_channel * light.shine_dir));
    program.set("u_shine_lit", glm::vec3(glm::dvec3(body.tint) * light.shine_lit * light.disc_weight));
    program.set("u_shine_limb_weight", static_cast<float>(light.shine_limb_weight));
    program.set("u_map_lod", static_cast<float>(map_lod(view, sphere, body, tex->second->width())));
    tex->second->bind(0);
    shadows.apply(program, casters, 1);
    if (sky) sky->set_sky_in_front(program);
    vao_.bind();
    // The limb's coverage (alpha, premultiplied colour) blends the colour; the G-buffer is written.
    glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    draw_sphere(program, view, oblate ? oblate_sphere(program, view, body, state, sphere) : sphere);
    glDisablei(GL_BLEND, 0);
    gl::check("body pass (" + body.name + ")");
}

}  // namespace cupola

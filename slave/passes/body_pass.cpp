#include "passes/body_pass.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "atmosphere/solar_scale.hpp"
#include "passes/body_map.hpp"

namespace cupola {

double sun_irradiance(const SunLight& sun, double d_m) {
    if (!sun.present || d_m <= 0.0) return 0.0;
    return atmosphere::sun_irradiance_scene_units(sun.radiance, sun.radius_m, sun.limb_u, d_m);
}

namespace {
std::string body_defines(bool oblate, bool after_sky, bool shadowed) {
    auto flag = [](const char* name, bool on) { return std::string("#define ") + name + (on ? " 1\n" : " 0\n"); };
    return flag("BODY_ECLIPSE", shadowed) + flag("BODY_AFTER_SKY", after_sky) + flag("BODY_OBLATE", oblate);
}
}  // namespace

BodyPass::BodyPass(const SceneConfig& scene) {
    bool any_oblate = false;
    for (const auto& b : scene.bodies) any_oblate = any_oblate || b.flattening > 0.0;
    for (int oblate = 0; oblate < (any_oblate ? 2 : 1); ++oblate)
        for (int after_sky = 0; after_sky < 2; ++after_sky)
            for (int shadowed = 0; shadowed < 2; ++shadowed)
                programs_[oblate][after_sky][shadowed] =
                    std::make_unique<GlProgram>("sphere.vert", "body.frag", body_defines(oblate, after_sky, shadowed));
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

const GlProgram& BodyPass::program(bool oblate, bool after_sky, bool shadowed) const {
    return *programs_[oblate][after_sky][shadowed];
}

SphereView BodyPass::oblate_sphere(const GlProgram& program, const ChannelView& view, const BodyConfig& body,
                                   const BodyState& state, const SphereView& sphere) {
    // u_to_sphere = B^T diag(1, 1, 1 / (1 - f)) B, B = channel -> body, all in double.
    const glm::dmat3 b = glm::transpose(glm::mat3_cast(state.orientation)) * view.channel_to_world;
    glm::dmat3 stretch(1.0), squeeze(1.0);
    stretch[2][2] = 1.0 / (1.0 - body.flattening);
    squeeze[2][2] = 1.0 - body.flattening;
    const glm::dmat3 to_sphere = glm::transpose(b) * stretch * b, from_sphere = glm::transpose(b) * squeeze * b;
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
    const GlProgram& program = this->program(oblate, sky != nullptr, shadowed);
    program.use();
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
    // The map's texels one pixel spans at the disc's centre: a small disc samples a coarser level.
    // A body with an atmosphere reads level 0, as the atmosphere's look-up does when it draws the
    // same surface (the two must agree).
    const double pixel_on_body_rad = pixel_angle_rad(*view.frustum) * sphere.distance_m / body.radius_m;
    const double texels = pixel_on_body_rad * tex->second->width() / (2.0 * std::numbers::pi);
    const double lod = body.atmosphere.present ? 0.0 : std::max(0.0, std::log2(std::max(texels, 1e-30)));
    program.set("u_map_lod", static_cast<float>(lod));
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

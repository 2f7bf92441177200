#include "passes/body_pass.hpp"

#include <cmath>
#include <numbers>

#include "atmosphere/solar_scale.hpp"
#include "passes/body_texture.hpp"

namespace cupola {

double sun_irradiance(const SunLight& sun, double d_m) {
    if (!sun.present || d_m <= 0.0) return 0.0;
    return atmosphere::sun_irradiance_scene_units(sun.radiance, sun.radius_m, sun.limb_u, d_m);
}

BodyPass::BodyPass(const SceneConfig& scene)
    : shadowed_("sphere.vert", "body.frag", "#define BODY_ECLIPSE 1\n#define BODY_AFTER_SKY 0\n"),
      plain_("sphere.vert", "body.frag", "#define BODY_ECLIPSE 0\n#define BODY_AFTER_SKY 0\n"),
      shadowed_after_sky_("sphere.vert", "body.frag", "#define BODY_ECLIPSE 1\n#define BODY_AFTER_SKY 1\n"),
      plain_after_sky_("sphere.vert", "body.frag", "#define BODY_ECLIPSE 0\n#define BODY_AFTER_SKY 1\n") {
    for (const auto& b : scene.bodies) {
        if (b.kind == BodyKind::Star) continue;
        const BodyImage img = load_body_image(b.texture);
        textures_[b.id] = std::make_unique<GlTexture>(img.width, img.height, img.rgb);
    }
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
                    const SkyInFrontSource* sky) {
    const auto tex = textures_.find(body.id);
    if (tex == textures_.end()) return;
    const glm::dvec3 to_sun = sun.position_m - state.position_m;  // double, world frame
    const double d_sun = glm::length(to_sun);
    const glm::dvec3 sun_dir = d_sun > 0.0 ? view.world_to_channel * (to_sun / d_sun) : glm::dvec3(0.0);
    const double lit = body.albedo / std::numbers::pi * sun_irradiance(sun, d_sun);

    const bool shadowed = casters.count > 0 && !body.atmosphere.present;
    const GlProgram& program =
        sky ? (shadowed ? shadowed_after_sky_ : plain_after_sky_) : (shadowed ? shadowed_ : plain_);
    program.use();
    program.set("u_channel_to_body", channel_to_body(view, state));
    program.set("u_sun_dir", glm::vec3(sun_dir));
    program.set("u_lit", glm::vec3(body.tint) * static_cast<float>(lit));
    program.set("u_reflectance", glm::vec3(body.tint) * static_cast<float>(body.albedo));
    program.set("u_texture", 0);
    tex->second->bind(0);
    shadows.apply(program, casters, 1);
    if (sky) sky->set_sky_in_front(program);
    vao_.bind();
    draw_sphere(program, view, sphere);
    gl::check("body pass (" + body.name + ")");
}

}  // namespace cupola

#include "passes/ring_drawer.hpp"

#include <cmath>
#include <numbers>

#include "passes/body_pass.hpp"
#include "passes/sphere_billboard.hpp"

namespace cupola {

glm::dvec3 ring_normal(const ChannelView& view, const BodyState& state) {
    return view.world_to_channel * (glm::mat3_cast(state.orientation) * glm::dvec3(0.0, 0.0, 1.0));
}

glm::dmat3 channel_to_stretched(const ChannelView& view, const BodyConfig& body, const BodyState& state) {
    const glm::dmat3 b = glm::transpose(glm::mat3_cast(state.orientation)) * view.channel_to_world;
    glm::dmat3 stretch(1.0);
    stretch[2][2] = 1.0 / (1.0 - body.flattening);
    return glm::transpose(b) * stretch * b;
}

RingDrawer::RingDrawer(const SceneConfig& scene) {
    for (const auto& b : scene.bodies) {
        if (!b.rings.present) continue;
        Rings r;
        r.profile = make_ring_profile(b.rings, load_body_image(b.rings.texture), b.radius_m);
        r.texture = std::make_unique<GlTexture>(static_cast<int>(r.profile.tau.size()), 1, r.profile.texels_rgb(),
                                                r.profile.mips);
        rings_.emplace(b.id, std::move(r));
    }
    if (rings_.empty()) return;
    program_ = std::make_unique<GlProgram>("sphere.vert", "ring.frag", "#define RING_AFTER_SKY 0\n");
    after_sky_program_ = std::make_unique<GlProgram>("sphere.vert", "ring.frag", "#define RING_AFTER_SKY 1\n");
}

const RingProfile* RingDrawer::profile(uint16_t body_id) const {
    const auto r = rings_.find(body_id);
    return r == rings_.end() ? nullptr : &r->second.profile;
}

void RingDrawer::set_shadow_uniforms(const GlProgram& program, const ChannelView& view, const BodyConfig& body,
                                     const BodyState& state) const {
    const Rings& r = rings_.at(body.id);
    program.set("u_ring_normal", glm::vec3(ring_normal(view, state)));
    program.set("u_ring_profile", static_cast<int>(kShadowUnit));
    program.set("u_ring_profile_map", glm::vec2(r.profile.radius_to_texture()));
    r.texture->bind(kShadowUnit);
}

void RingDrawer::draw(const ChannelView& view, const FrameBody& fb, const SunLight& sun,
                      const SkyInFrontSource* sky) const {
    const auto it = rings_.find(fb.body->id);
    if (it == rings_.end() || fb.light.disc_weight <= 0.0 || !sun.present) return;
    const BodyConfig& body = *fb.body;
    const Rings& r = it->second;
    const glm::dvec3 to_sun = sun.position_m - fb.state->position_m;
    const double d_sun = glm::length(to_sun);
    const double radiance_per_iof = body.rings.phase_albedo / 4.0 * sun_irradiance(sun, d_sun) / std::numbers::pi;
    const GlProgram& p = sky ? *after_sky_program_ : *program_;
    p.use();
    if (sky) sky->set_sky_in_front(p);
    p.set("u_camera", glm::vec3(-fb.sphere.center_dir * (fb.sphere.distance_m / body.radius_m)));
    p.set("u_normal", glm::vec3(ring_normal(view, *fb.state)));
    p.set("u_to_sphere", glm::mat3(channel_to_stretched(view, body, *fb.state)));
    p.set("u_sun_dir", glm::vec3(view.world_to_channel * (to_sun / d_sun)));
    p.set("u_sun_radius_rad", static_cast<float>(std::asin(std::min(1.0, sun.radius_m / d_sun))));
    p.set("u_profile", 0);
    p.set("u_profile_map", glm::vec2(r.profile.radius_to_texture()));
    p.set("u_profile_texels", static_cast<float>(r.profile.tau.size()));
    p.set("u_lit", glm::vec3(body.rings.tint) * static_cast<float>(radiance_per_iof * fb.light.disc_weight));
    p.set("u_limb_aa", fb.light.small_disc ? 1 : 0);
    p.set("u_supersample", fb.light.supersample);
    r.texture->bind(0);
    vao_.bind();
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    draw_sphere(p, view, make_sphere_view(view, fb.state->position_m, r.profile.outer_radius * body.radius_m * 1.01));
    glDisablei(GL_BLEND, 0);
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl::check("ring pass (" + body.name + ")");
}

}  // namespace cupola

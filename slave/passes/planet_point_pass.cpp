#include "passes/planet_point_pass.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>

#include "passes/atmosphere_pass.hpp"
#include "passes/point_sprite_view.hpp"
#include "passes/star_pass.hpp"

namespace cupola {

PlanetPointPass::PlanetPointPass()
    : program_("planet_point.vert", "planet_point.frag", "#define POINT_AFTER_SKY 0\n"),
      after_sky_program_("planet_point.vert", "planet_point.frag", "#define POINT_AFTER_SKY 1\n") {}

bool PlanetPointPass::visible_at(const PlanetLight& light, double exposure) {
    if (exposure <= 0.0) return true;
    const glm::dvec3 color = light.point_color();
    const double sigma = light.point_sigma_rad;
    const double peak = std::max({color.r, color.g, color.b}) / (2.0 * std::numbers::pi * sigma * sigma);
    return peak * exposure >= StarPass::kMinDisplay;
}

int PlanetPointPass::prepare_at(const FrameContext& frame, bool after_sky) {
    if (after_sky && !sky_) throw std::logic_error("planet points: drawn after the sky without the air in front");
    frame_ = &frame;
    after_sky_ = after_sky;
    in_view_.clear();
    const ChannelFrustum& f = *frame.view.frustum;
    // The largest sprite's half-width (stars.vert clamps a point to 255 pixels) and the guard band.
    const double reach_rad = std::min((128.0 + PointSpriteView::kGuardPx) * pixel_angle_rad(f), 0.5 * std::numbers::pi);
    const double exposure = frame.snap->settings.exposure;
    for (const FrameBody& b : frame.far_to_near)
        if (b.light.has_point() && visible_at(b.light, exposure) &&
            !sphere_outside_frustum(f, b.sphere.center_dir, std::sin(reach_rad)))
            in_view_.push_back(&b);
    return in_view_.empty() ? 0 : 1;
}

void PlanetPointPass::set_occluders(const GlProgram& program, const FrameBody& body) const {
    // The nearer bodies that can hide this one, largest on screen first. A star's point carries
    // only what they leave of its disc already (star_visible_fraction): none hide it again.
    std::vector<std::pair<double, glm::vec4>> nearer;
    if (body.body->kind == BodyKind::Star) {
        program.set("u_occluder_count", 0);
        return;
    }
    for (const FrameBody& o : frame_->far_to_near) {
        if (o.body->kind == BodyKind::Star || o.sphere.distance_m >= body.sphere.distance_m) continue;
        const double radius_rad =
            o.sphere.sin_alpha >= 1.0 ? std::numbers::pi : sphere_angular_radius_rad(o.sphere.sin_alpha);
        nearer.push_back({radius_rad, glm::vec4(glm::vec3(o.sphere.center_dir), static_cast<float>(radius_rad))});
    }
    std::sort(nearer.begin(), nearer.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const int count = std::min<int>(kMaxOccluders, static_cast<int>(nearer.size()));
    glm::vec4 occluders[kMaxOccluders];
    for (int i = 0; i < count; ++i) occluders[i] = nearer[static_cast<size_t>(i)].second;
    if (count > 0) program.set("u_occluders", occluders, count);
    program.set("u_occluder_count", count);
}

void PlanetPointPass::draw_point(const GlProgram& program, const FrameBody& b) const {
    program.set("u_dir", glm::vec3(b.sphere.center_dir));
    program.set("u_color", glm::vec3(b.light.point_color()));
    program.set("u_sigma_rad", static_cast<float>(b.light.point_sigma_rad));
    set_occluders(program, b);
    glDrawArrays(GL_POINTS, 0, 1);
}

void PlanetPointPass::draw(const PassInputs&, int) {
    const GlProgram& program = after_sky_ ? after_sky_program_ : program_;
    const ChannelView& view = frame_->view;
    const ChannelFrustum& f = *view.frustum;
    const PointSpriteView sprites = point_sprite_view(f);
    program.use();
    program.set("u_projection", glm::mat4(sprites.wide.projection(0.1, 10.0)));
    program.set("u_px_per_tangent", glm::vec2(sprites.px_per_tangent_x, sprites.px_per_tangent_y));
    program.set("u_exposure", static_cast<float>(frame_->snap->settings.exposure));
    program.set("u_min_display", static_cast<float>(StarPass::kMinDisplay));
    program.set("u_fixed_reach_sigma", static_cast<float>(StarPass::kFixedReachSigma));
    program.set("u_tangents", view.tangents());
    program.set("u_size", view.size());
    if (after_sky_) sky_->set_sky_in_front(program);
    bind_guarded_viewport(f);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glEnablei(GL_BLEND, 0);
    glBlendFuncSeparatei(0, GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    vao_.bind();
    for (const FrameBody* b : in_view_) draw_point(program, *b);
    points_drawn_ += static_cast<long>(in_view_.size());
    glDisablei(GL_BLEND, 0);
    unbind_guarded_viewport(f);
    gl::check("planet points");
}

}  // namespace cupola

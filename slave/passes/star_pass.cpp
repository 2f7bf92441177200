#include "passes/star_pass.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "passes/point_sprite_view.hpp"
#include "passes/sky_view_gpu.hpp"
#include "passes/sphere_billboard.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

StarPass::StarPass(const StarFieldConfig& config, std::vector<Star> stars)
    : config_(config), program_("stars.vert", "stars.frag"), vertices_({3, 1, 1}) {
    std::stable_sort(stars.begin(), stars.end(), [](const Star& a, const Star& b) { return a.v_mag < b.v_mag; });
    std::vector<float> data;
    data.reserve(stars.size() * 5);
    std::vector<glm::vec4> dir_and_magnitude;
    for (const auto& s : stars) {
        const glm::dvec3 d = s.direction();
        data.insert(data.end(),
                    {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z),
                     static_cast<float>(config.zero_mag_flux * std::pow(10.0, -0.4 * s.v_mag)), s.b_minus_v});
        magnitudes_.push_back(s.v_mag);
        dir_and_magnitude.emplace_back(glm::vec3(d), s.v_mag);
    }
    vertices_.upload(data);
    sky_weights_ = std::make_unique<StarSkyWeights>(dir_and_magnitude);
    vertices_.add_float_attribute(3, sky_weights_->buffer(), 4);
}

double StarPass::visible_magnitude(double exposure) const {
    if (!(exposure > 0.0) || !(config_.zero_mag_flux > 0.0)) return -1e9;
    const double sigma = config_.psf_sigma_arcmin / 60.0 * std::numbers::pi / 180.0;
    const double min_flux = kMinDisplay * 2.0 * std::numbers::pi * sigma * sigma / exposure;
    return -2.5 * std::log10(min_flux / config_.zero_mag_flux);
}

int StarPass::prepare_at(const FrameContext& frame, bool after_sky) {
    view_ = &frame.view;
    after_sky_ = after_sky;
    exposure_ = frame.snap->settings.exposure;
    occluder_ = largest_occluder(frame);
    sky_ = sky_source_ ? sky_source_->star_sky(frame) : StarSky{};
    twinkle_ = twinkle_for(*frame.snap, sky_);
    magnitude_limit_ =
        std::min({config_.magnitude_limit, static_cast<double>(frame.snap->settings.star_magnitude_limit),
                  visible_magnitude(frame.snap->settings.exposure)});
    const bool any = !magnitudes_.empty() && magnitudes_.front() <= magnitude_limit_;
    return any ? 1 : 0;
}

StarTwinkle StarPass::twinkle_for(const Snapshot& snap, const StarSky& sky) {
    StarTwinkle t;
    t.time_s = snap.settings.twinkle_time_s;
    const TwinkleMode mode = twinkle_mode_of(snap.settings.flags);
    if (mode == TwinkleMode::Off) return t;
    const float d_m = sky.table_in.x;
    const bool in_air = sky.table && d_m < sky.params.top_radius_m;
    if (in_air) {
        t.sigma_zenith = shading::twinkle_sigma_zenith(d_m - sky.params.bottom_radius_m);
        t.zenith_world = -sky.center_dir_world;
    } else if (mode == TwinkleMode::Forced) {
        t.sigma_zenith = shading::twinkle_sigma_zenith(0.0f);
    }
    return t;
}

StarOccluder StarPass::largest_occluder(const FrameContext& frame) {
    StarOccluder o;
    double best = 0.0;
    for (const FrameBody& b : frame.far_to_near) {
        const double s = b.sphere.sin_alpha;
        if (b.body->kind == BodyKind::Star || !(s > best) || !(s < 1.0)) continue;
        best = s;
        o.center_dir = glm::vec3(b.sphere.center_dir);
        o.radius_rad = static_cast<float>(sphere_angular_radius_rad(s));
    }
    return o;
}

void StarPass::draw(const PassInputs&, int) { draw(*view_, magnitude_limit_, exposure_, occluder_, sky_, after_sky_); }

void StarPass::draw(const ChannelView& view, double magnitude_limit, double exposure, StarOccluder occluder,
                    const StarSky& sky, bool after_sky) {
    if (after_sky && !sky.table)
        throw std::logic_error("star pass: drawn after the sky without the sky's table to take the air in front from");
    const auto count = static_cast<GLsizei>(
        std::upper_bound(magnitudes_.begin(), magnitudes_.end(), static_cast<float>(magnitude_limit)) -
        magnitudes_.begin());
    if (count == 0) return;
    if (sky.table) {  // the same table the atmosphere's draw looks up, rendered here when not current
        sky.table->update(sky.table_in.x, sky.table_in.y);
        if (sky.moon_table) sky.moon_table->update(sky.table_in.x, sky.moon_mu);
        sky_weights_->update(sky, count);
    }
    program_.use();
    program_.set("u_sky_on", !sky.table ? 0 : after_sky ? 2 : 1);
    const ChannelFrustum& f = *view.frustum;
    const double sigma = config_.psf_sigma_arcmin / 60.0 * std::numbers::pi / 180.0;
    // Guard band: stars whose centre lies just outside still spill light into the image.
    const PointSpriteView sprites = point_sprite_view(f);
    bind_guarded_viewport(f);

    program_.set("u_world_to_channel", glm::mat3(view.world_to_channel));
    program_.set("u_projection", glm::mat4(sprites.wide.projection(0.1, 10.0)));
    program_.set("u_px_per_tangent", glm::vec2(sprites.px_per_tangent_x, sprites.px_per_tangent_y));
    program_.set("u_sigma_rad", static_cast<float>(sigma));
    program_.set("u_exposure", static_cast<float>(exposure));
    program_.set("u_twinkle_sigma_zenith", twinkle_.sigma_zenith);
    program_.set("u_twinkle_zenith", twinkle_.zenith_world);
    program_.set("u_twinkle_time_s", twinkle_.time_s);
    program_.set("u_min_display", static_cast<float>(kMinDisplay));
    program_.set("u_fixed_reach_sigma", static_cast<float>(kFixedReachSigma));
    program_.set("u_occluder_dir", occluder.center_dir);
    program_.set("u_occluder_rad", occluder.radius_rad);
    // Two pixels (at the centre, where a pixel spans the widest angle) beyond a star's reach.
    program_.set("u_pixel_rad", static_cast<float>(pixel_angle_rad(f)));
    program_.set("u_tangents", view.tangents());
    program_.set("u_size", view.size());
    glEnable(GL_PROGRAM_POINT_SIZE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    vertices_.bind();
    if (sky.table) {  // the stars up to the last one the eye sees (star_weights.frag wrote the count)
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, sky_weights_->draw_command());
        glDrawArraysIndirect(GL_POINTS, nullptr);
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    } else {
        glDrawArrays(GL_POINTS, 0, count);
    }
    glDisable(GL_BLEND);
    unbind_guarded_viewport(f);
    gl::check("star pass");
}

}  // namespace cupola

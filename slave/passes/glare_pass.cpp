#include "passes/glare_pass.hpp"

#include <algorithm>
#include <cmath>

#include "glare/glare_frame.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

namespace {
double luminance(const glm::vec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
}  // namespace

GlarePass::GlarePass(const SceneConfig& scene, const GlareProbe& probe)
    : scene_(&scene), probe_(probe), program_("sphere.vert", "glare.frag") {}

int GlarePass::prepare(const FrameContext& frame) {
    frame_ = &frame;
    return frame.snap->glare.empty() ? 0 : 1;
}

void GlarePass::draw(const PassInputs&, int) { draw(frame_->view, *frame_->snap, probe_); }

double GlarePass::extent_rad(const GlareSource& source, double exposure) const {
    const GlareConfig& c = scene_->glare;
    const double max_extent = glm::radians(c.extent_deg);
    const double scale = luminance(source.irradiance) * source.visible_fraction * exposure * c.strength;
    const double floor = 0.25 * c.min_display;
    if (floor <= 0.0 || scale <= 0.0) return scale > 0.0 ? max_extent : 0.0;
    auto value = [&](double theta) {
        const float t = static_cast<float>(theta);
        return scale * (shading::glare_bloom(t) + shading::glare_flare(t));
    };
    if (value(max_extent) >= floor) return max_extent;
    double lo = 0.0, hi = max_extent;  // the PSF falls monotonically
    for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (value(mid) >= floor ? lo : hi) = mid;
    }
    return hi;
}

void GlarePass::draw(const ChannelView& view, const Snapshot& snap, const GlareProbe& probe) {
    const GlareConfig& c = scene_->glare;
    bool bound = false;
    for (const GlareSource& src : snap.glare) {
        float fraction = src.visible_fraction;
        glm::dvec3 center_world = glm::dvec3(src.direction) + glm::dvec3(src.centroid_offset);
        if (c.visibility == GlareVisibilityMode::PerChannel) {
            // The naive channel: its own query, and only while the source's centre is in its view.
            const glm::dvec3 d = view.world_to_channel * glm::dvec3(src.direction);
            const auto own = probe.own_fraction(src);
            const bool centre_in_view = d.z < 0.0 && -d.x / d.z >= -view.frustum->tan_left() &&
                                        -d.x / d.z < view.frustum->tan_right() &&
                                        -d.y / d.z >= -view.frustum->tan_down() && -d.y / d.z < view.frustum->tan_up();
            if (!own || !centre_in_view) continue;
            fraction = *own;
            center_world = glm::dvec3(src.direction);
        }
        GlareSource shown = src;
        shown.visible_fraction = fraction;
        const double extent = extent_rad(shown, snap.settings.exposure);
        if (!(extent > 0.0)) continue;
        const GlareFrame frame = glare_frame(center_world, snap.camera_orientation);
        const glm::dvec3 cc = view.world_to_channel * frame.center;
        // A quick reject: the glare's cone entirely outside this channel (a generous bound).
        const double half_diag = std::atan(std::hypot(std::max(view.frustum->tan_left(), view.frustum->tan_right()),
                                                      std::max(view.frustum->tan_down(), view.frustum->tan_up())));
        const double off_axis = std::acos(std::clamp(-cc.z, -1.0, 1.0));
        if (off_axis > half_diag + extent) continue;

        // The billboard: in the plane at the scaled distance k along the centre, normal toward
        // the camera position, a square circumscribing the cone of half-angle `extent`.
        SphereView quad;
        const double k = SphereView::kScaledDistance;
        const double h = k * std::tan(extent);
        const glm::dvec3 e1 = view.world_to_channel * frame.right, e2 = view.world_to_channel * frame.up;
        const glm::dvec3 p = cc * k;
        quad.corners = {glm::vec3(p - h * e1 - h * e2), glm::vec3(p + h * e1 - h * e2), glm::vec3(p - h * e1 + h * e2),
                        glm::vec3(p + h * e1 + h * e2)};
        quad.center_dir = cc;
        quad.distance_m = 1.0;
        quad.radius_m = 0.0;

        if (!bound) {
            program_.use();
            program_.set("u_glare.strength", static_cast<float>(c.strength));
            program_.set("u_glare.halo_radius_rad", static_cast<float>(glm::radians(c.halo_radius_deg)));
            program_.set("u_glare.halo_width_rad", static_cast<float>(glm::radians(c.halo_width_deg)));
            program_.set("u_glare.halo_fraction", static_cast<float>(c.halo_fraction));
            program_.set("u_glare.streak_count", static_cast<float>(c.streak_count));
            program_.set("u_glare.streak_contrast", static_cast<float>(c.streak_contrast));
            program_.set("u_glare.phase", snap.settings.glare_phase);
            // Additive in colour; the coverage (alpha) stays what the scene wrote.
            glEnablei(GL_BLEND, 0);
            glBlendFuncSeparatei(0, GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
            vao_.bind();
            bound = true;
        }
        program_.set("u_glare.extent_rad", static_cast<float>(extent));
        program_.set("u_center", glm::vec3(cc));
        program_.set("u_e1", glm::vec3(e1));
        program_.set("u_e2", glm::vec3(e2));
        program_.set("u_irradiance", src.irradiance * fraction);
        draw_sphere(program_, view, quad);
        ++drawn_;
    }
    if (bound) glDisablei(GL_BLEND, 0);
    gl::check("glare pass");
}

}  // namespace cupola

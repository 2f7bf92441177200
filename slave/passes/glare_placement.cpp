#include "passes/glare_placement.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "glare/glare_frame.hpp"
#include "shading/shared_shading.hpp"

namespace cupola {

namespace {

double luminance(const glm::vec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// The visible fraction this channel draws a source with, and the direction of its glare centre;
// nothing where the per-channel mode's channel does not see the source's centre.
std::optional<std::pair<float, glm::dvec3>> drawn_fraction(const GlareConfig& c, const ChannelView& view,
                                                           const GlareSource& src, const GlareProbe& probe) {
    if (c.visibility != GlareVisibilityMode::PerChannel)
        return std::make_pair(src.visible_fraction, glm::dvec3(src.direction) + glm::dvec3(src.centroid_offset));
    // The naive channel: its own query, and only while the source's centre is in its view.
    const glm::dvec3 d = view.world_to_channel * glm::dvec3(src.direction);
    const auto own = probe.own_fraction(src);
    const ChannelFrustum& f = *view.frustum;
    const bool centre_in_view = d.z < 0.0 && -d.x / d.z >= -f.tan_left() && -d.x / d.z < f.tan_right() &&
                                -d.y / d.z >= -f.tan_down() && -d.y / d.z < f.tan_up();
    if (!own || !centre_in_view) return std::nullopt;
    return std::make_pair(*own, glm::dvec3(src.direction));
}

}  // namespace

double glare_extent_rad(const GlareConfig& c, const GlareSource& source, double exposure) {
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

std::vector<GlarePlacement> place_glare(const GlareConfig& c, const ChannelView& view, const Snapshot& snap,
                                        const GlareProbe& probe) {
    std::vector<GlarePlacement> out;
    // A quick reject: the glare's cone entirely outside this channel (a generous bound).
    const ChannelFrustum& f = *view.frustum;
    const double half_diag =
        std::atan(std::hypot(std::max(f.tan_left(), f.tan_right()), std::max(f.tan_down(), f.tan_up())));
    for (const GlareSource& src : snap.glare) {
        const auto drawn = drawn_fraction(c, view, src, probe);
        if (!drawn) continue;
        GlareSource shown = src;
        shown.visible_fraction = drawn->first;
        const double extent = glare_extent_rad(c, shown, snap.settings.exposure);
        if (!(extent > 0.0)) continue;
        const GlareFrame frame = glare_frame(drawn->second, snap.camera_orientation);
        GlarePlacement g;
        g.center = view.world_to_channel * frame.center;
        g.e1 = view.world_to_channel * frame.right;
        g.e2 = view.world_to_channel * frame.up;
        g.irradiance = src.irradiance * drawn->first;
        g.extent_rad = extent;
        if (std::acos(std::clamp(-g.center.z, -1.0, 1.0)) > half_diag + extent) continue;
        out.push_back(g);
    }
    return out;
}

void set_glare_params(const GlProgram& program, const GlareConfig& c, float phase) {
    program.set("u_glare.strength", static_cast<float>(c.strength));
    program.set("u_glare.halo_radius_rad", static_cast<float>(glm::radians(c.halo_radius_deg)));
    program.set("u_glare.halo_width_rad", static_cast<float>(glm::radians(c.halo_width_deg)));
    program.set("u_glare.halo_fraction", static_cast<float>(c.halo_fraction));
    program.set("u_glare.streak_count", static_cast<float>(c.streak_count));
    program.set("u_glare.streak_contrast", static_cast<float>(c.streak_contrast));
    program.set("u_glare.phase", phase);
}

void set_glare_placement(const GlProgram& program, const GlarePlacement& g) {
    program.set("u_glare.extent_rad", static_cast<float>(g.extent_rad));
    program.set("u_center", glm::vec3(g.center));
    program.set("u_e1", glm::vec3(g.e1));
    program.set("u_e2", glm::vec3(g.e2));
    program.set("u_irradiance", g.irradiance);
}

}  // namespace cupola

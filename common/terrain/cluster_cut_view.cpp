#include "terrain/cluster_cut_view.hpp"

#include <algorithm>
#include <cmath>

namespace cupola::terrain {

namespace {

ChannelCone channel_cone(const ChannelFrustum& f, const glm::dmat3& body_from_dome) {
    return {glm::transpose(body_from_dome * f.rotation()),
            glm::dvec4(f.tan_left(), f.tan_right(), f.tan_down(), f.tan_up())};
}

glm::dmat3 body_from_dome(const ClusterConfig& cluster, const glm::dmat3& body_from_world,
                          const glm::dquat& camera_orientation) {
    return body_from_world * glm::mat3_cast(camera_orientation) * dome_tilt_rotation(cluster.dome.tilt_deg);
}

}  // namespace

// The shorter side of a pixel, as an angle, at the corners and the centre (at a corner of a
// planar channel the radial side is the shorter: a square root of the solid angle would be the
// geometric mean, too large).
double finest_pixel_rad(const ChannelFrustum& f) {
    const double w = f.width(), h = f.height();
    const auto angle = [&](const glm::dvec2& a, const glm::dvec2& b) {
        return std::acos(std::clamp(glm::dot(f.pixel_to_dome_direction(a), f.pixel_to_dome_direction(b)), -1.0, 1.0));
    };
    double finest = 1e9;
    for (const glm::dvec2 p : {glm::dvec2(0.0, 0.0), glm::dvec2(w - 1, 0.0), glm::dvec2(0.0, h - 1),
                               glm::dvec2(w - 1, h - 1), glm::dvec2(0.5 * w, 0.5 * h)})
        finest = std::min({finest, angle(p, p + glm::dvec2(1, 0)), angle(p, p + glm::dvec2(0, 1))});
    return finest;
}

CutView cut_view_for_cluster(const ClusterConfig& cluster, const glm::dvec3& camera_body_m,
                             const glm::dmat3& body_from_world, const glm::dquat& camera_orientation,
                             const std::optional<glm::dvec3>& eye_room_m) {
    CutView v;
    v.camera_m = camera_body_m;
    const glm::dmat3 to_body = body_from_dome(cluster, body_from_world, camera_orientation);
    v.pixel_rad = 1e9;
    for (const ChannelConfig& ch : cluster.channels) {
        const ChannelFrustum f = eye_room_m ? ch.frustum_seen_from(*eye_room_m) : ch.frustum();
        v.channels.push_back(channel_cone(f, to_body));
        v.pixel_rad = std::min(v.pixel_rad, finest_pixel_rad(f));
    }
    return v;
}

CutView cut_view_for_channel(const ClusterConfig& cluster, const ChannelConfig& channel,
                             const glm::dvec3& camera_body_m, const glm::dmat3& body_from_world,
                             const glm::dquat& camera_orientation) {
    CutView v;
    v.camera_m = camera_body_m;
    const ChannelFrustum f = channel.frustum();
    v.channels.push_back(channel_cone(f, body_from_dome(cluster, body_from_world, camera_orientation)));
    v.pixel_rad = finest_pixel_rad(f);
    return v;
}

}  // namespace cupola::terrain

#include "glare/glare_sharing.hpp"

#include <algorithm>
#include <cmath>

#include "glare/glare_frame.hpp"
#include "projection/dome_frame.hpp"

namespace cupola {

GlareSharing::GlareSharing(const ClusterConfig& cluster)
    : cluster_(&cluster), dome_from_camera_(glm::transpose(dome_tilt_rotation(cluster.dome.tilt_deg))) {
    for (const auto& c : cluster.channels) frusta_.push_back(c.frustum());
}

bool GlareSharing::channel_may_see(int channel_index, const glm::dquat& camera_orientation, const glm::dvec3& direction,
                                   double angular_radius) const {
    const glm::dmat3 dome_from_world = dome_from_camera_ * glm::transpose(glm::mat3_cast(camera_orientation));
    return disc_may_touch_frustum(frusta_.at(static_cast<size_t>(channel_index)), dome_from_world,
                                  glare_frame(direction, camera_orientation), angular_radius);
}

void GlareSharing::apply(Snapshot& snap, const std::map<int, FrameReport>& reports, uint64_t measured_frame) {
    for (GlareSource& g : snap.glare) {
        double total = 0.0;
        float visible[GlareMeasurement::kWedges] = {};
        bool complete = true;
        for (size_t i = 0; i < cluster_->channels.size(); ++i) {
            const int id = cluster_->channels[i].id;
            const auto rep = reports.find(id);
            const GlareMeasurement* m = nullptr;
            if (rep != reports.end() && rep->second.frame == measured_frame)
                for (const auto& gm : rep->second.glare)
                    if (gm.body == g.body && gm.star == g.star && gm.frame == measured_frame) m = &gm;
            if (m) {
                total += m->total_sr;
                for (int w = 0; w < GlareMeasurement::kWedges; ++w) visible[w] += m->visible_sr[w];
                continue;
            }
            // No measurement: fine if the channel reported this frame (it saw nothing of the
            // source), or if it cannot see the source at all.
            const bool reported = rep != reports.end() && rep->second.frame == measured_frame;
            if (!reported && channel_may_see(static_cast<int>(i), snap.camera_orientation, glm::dvec3(g.direction),
                                             g.angular_radius))
                complete = false;
        }
        if (!complete) ++counts_.missing;
        if (!complete || !(total > 0.0)) {
            ++counts_.analytic;
            continue;  // keep the analytic value
        }
        double seen = 0.0;
        for (float v : visible) seen += v;
        g.visible_fraction = static_cast<float>(std::clamp(seen / total, 0.0, 1.0));
        const GlareFrame frame = glare_frame(glm::dvec3(g.direction), snap.camera_orientation);
        g.centroid_offset = glm::vec3(glare_centroid_offset(frame, visible, g.angular_radius));
        g.origin = GlareOrigin::Measured;
        g.measured_frame = measured_frame;
        ++counts_.measured;
    }
}

}  // namespace cupola

#pragma once
// The cluster-wide glare visibility (Ekelin & Fernqvist 2009, section 5.1.1: the slaves
// report, the master shares). Each channel reports, per source, the solid angle of the source's disc in the
// directions it owns (every dome direction has exactly one owner, so nothing counts twice),
// total and unoccluded per wedge. For frame N+1 the master sums frame N's reports:
//   visible fraction = sum(visible) / sum(total), offset toward the visible part from the wedges,
// and writes them into the snapshot, so the shared values lag the queries by one frame. Where a
// channel that may see the source did not report frame N (lost report, dropped or restarted
// slave), or no channel saw it, the snapshot keeps the analytic value of spherical occluders
// (common/glare/glare_sources), so the glare neither freezes nor flickers.
#include <map>

#include "config/cluster_config.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

struct GlareShareCounts {
    uint64_t measured = 0;  // source-frames that used the cluster's measurement
    uint64_t analytic = 0;  // source-frames that fell back to the analytic value
    uint64_t missing = 0;   // of those, because a channel that may see the source did not report
};

class GlareSharing {
public:
    explicit GlareSharing(const ClusterConfig& cluster);

    // snap: the next frame's snapshot (sources with their analytic visibility); reports: the
    // channels' reports of measured_frame (by channel id).
    void apply(Snapshot& snap, const std::map<int, FrameReport>& reports, uint64_t measured_frame);

    // Whether a channel's frustum may hold part of a source's disc (centre direction and radius,
    // world frame) for this camera orientation.
    bool channel_may_see(int channel_index, const glm::dquat& camera_orientation, const glm::dvec3& direction,
                         double angular_radius) const;

    const GlareShareCounts& counts() const { return counts_; }

private:
    const ClusterConfig* cluster_;
    std::vector<ChannelFrustum> frusta_;
    glm::dmat3 dome_from_camera_;
    GlareShareCounts counts_;
};

}  // namespace cupola

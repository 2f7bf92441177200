#pragma once
// The view a terrain cut is chosen for: the whole dome of a cluster, from the snapshot's camera.
// Every node builds the same one from the cluster configuration (all channels, not its own) and
// the snapshot, so the cut is the same on every node.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "config/cluster_config.hpp"
#include "terrain/terrain_cut.hpp"

#include <optional>

namespace cupola::terrain {

// camera_body_m: the camera in the body-fixed frame (m); body_from_world: world -> body-fixed
// rotation; camera_orientation: the snapshot's camera (camera frame -> world); eye_room_m: the
// snapshot's head, which the frusta of channels given as screens follow (none: as configured).
CutView cut_view_for_cluster(const ClusterConfig& cluster, const glm::dvec3& camera_body_m,
                             const glm::dmat3& body_from_world, const glm::dquat& camera_orientation,
                             const std::optional<glm::dvec3>& eye_room_m = std::nullopt);

// One channel alone, as the systems that pick detail per channel do (for comparison only).
CutView cut_view_for_channel(const ClusterConfig& cluster, const ChannelConfig& channel,
                             const glm::dvec3& camera_body_m, const glm::dmat3& body_from_world,
                             const glm::dquat& camera_orientation);

// The angle of the shortest side of a channel's pixels (at a corner, for a planar projection).
double finest_pixel_rad(const ChannelFrustum& f);

}  // namespace cupola::terrain

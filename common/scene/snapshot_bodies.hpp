#pragma once
// Looking bodies up in a snapshot: by scene id, and the scene's star (the light and the glare's
// first source).
#include "config/scene_config.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// The snapshot's state of body `id`, or nullptr when the snapshot does not carry it.
const BodyState* find_body(const Snapshot& snap, uint16_t id);

// The first body of the snapshot that the scene declares a star (ids outside the scene are
// skipped), or nullptr.
const BodyState* find_star(const Snapshot& snap, const SceneConfig& scene);

}  // namespace cupola

#include "scene/snapshot_bodies.hpp"

namespace cupola {

const BodyState* find_body(const Snapshot& snap, uint16_t id) {
    for (const auto& st : snap.bodies)
        if (st.id == id) return &st;
    return nullptr;
}

const BodyState* find_star(const Snapshot& snap, const SceneConfig& scene) {
    for (const auto& st : snap.bodies)
        if (st.id < scene.bodies.size() && scene.bodies[st.id].kind == BodyKind::Star) return &st;
    return nullptr;
}

}  // namespace cupola

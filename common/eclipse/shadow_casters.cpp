#include "eclipse/shadow_casters.hpp"

#include <algorithm>

#include "scene/snapshot_bodies.hpp"

namespace cupola {

std::vector<std::vector<uint16_t>> shadow_candidates(const SceneConfig& scene) {
    std::vector<std::vector<uint16_t>> out(scene.bodies.size());
    auto add = [&](uint16_t receiver, uint16_t caster) {
        auto& v = out.at(receiver);
        if (receiver != caster && std::find(v.begin(), v.end(), caster) == v.end()) v.push_back(caster);
    };
    for (const auto& g : scene.shadows.groups) {
        for (uint16_t c : g.children) {
            add(g.parent, c);
            add(c, g.parent);
            if (g.siblings_shadow_each_other)
                for (uint16_t other : g.children) add(c, other);
        }
    }
    return out;
}

double shadow_bounding_radius(const BodyConfig& body) {
    return body.atmosphere.present ? std::max(body.atmosphere.parameters.top_radius, body.radius_m) : body.radius_m;
}

bool penumbra_reaches(const glm::dvec3& sun, double sun_r, const glm::dvec3& caster, double caster_r,
                      const glm::dvec3& receiver, double receiver_r) {
    const glm::dvec3 axis = caster - sun;
    const double length = glm::length(axis);
    if (length <= sun_r + caster_r) return false;  // degenerate: caster touching the Sun
    const glm::dvec3 u = axis / length;
    const glm::dvec3 w = receiver - caster;
    const double x = glm::dot(w, u);                 // behind the caster along the axis
    if (x < -(receiver_r + caster_r)) return false;  // the receiver is on the Sun's side
    const double perp = glm::length(w - x * u);
    const double r_p = caster_r + std::max(x, 0.0) * (sun_r + caster_r) / length;
    // The cone's slant makes the perpendicular test exact only to first order: keep a margin.
    return perp - r_p < receiver_r * 1.01 + 1e-3 * r_p;
}

EclipseSun eclipse_sun(const SceneConfig& scene, const Snapshot& snap) {
    EclipseSun s;
    if (const BodyState* st = find_star(snap, scene)) {
        const BodyConfig& b = scene.bodies[st->id];
        s = {true, st->position_m, b.radius_m, b.limb_darkening_u};
    }
    return s;
}

ShadowCasting::ShadowCasting(const SceneConfig& scene, std::map<uint16_t, glm::vec3> umbra_light)
    : scene_(scene), candidates_(shadow_candidates(scene)), umbra_light_(std::move(umbra_light)) {}

std::vector<uint16_t> ShadowCasting::active_casters(const Snapshot& snap, uint16_t receiver) const {
    std::vector<uint16_t> out;
    if (receiver >= candidates_.size() || candidates_[receiver].empty()) return out;
    if (shadow_mode_of(snap.settings.flags) == ShadowMode::Off) return out;
    const EclipseSun sun = eclipse_sun(scene_, snap);
    if (!sun.present) return out;
    const BodyState* r = find_body(snap, receiver);
    if (!r) return out;
    std::vector<std::pair<double, uint16_t>> hits;
    for (uint16_t c : candidates_[receiver]) {
        const BodyState* cs = find_body(snap, c);
        if (!cs) continue;
        if (penumbra_reaches(sun.position_m, sun.radius_m, cs->position_m, scene_.bodies[c].radius_m, r->position_m,
                             shadow_bounding_radius(scene_.bodies[receiver])))
            hits.push_back({glm::length(cs->position_m - r->position_m), c});
    }
    std::sort(hits.begin(), hits.end());
    for (const auto& h : hits)
        if (out.size() < static_cast<size_t>(shading::ECLIPSE_MAX_CASTERS)) out.push_back(h.second);
    return out;
}

shading::EclipseCasters ShadowCasting::casters_for(const Snapshot& snap, uint16_t receiver,
                                                   const glm::dmat3& to_frame) const {
    shading::EclipseCasters e = shading::eclipse_no_casters();
    const std::vector<uint16_t> ids = active_casters(snap, receiver);
    if (ids.empty()) return e;
    const EclipseSun sun = eclipse_sun(scene_, snap);
    const BodyState* receiver_state = find_body(snap, receiver);
    const glm::dvec3 receiver_pos = receiver_state ? receiver_state->position_m : glm::dvec3(0.0);
    e.mode = static_cast<int>(shadow_mode_of(snap.settings.flags));  // ShadowMode values are ECLIPSE_MODE_*
    e.limb_u = static_cast<float>(sun.limb_u);
    e.butterworth_order = static_cast<float>(scene_.shadows.butterworth_order);
    e.sun_position_m = glm::vec3(to_frame * (sun.position_m - receiver_pos));
    e.sun_radius_m = static_cast<float>(sun.radius_m);
    for (uint16_t id : ids) {
        for (const auto& st : snap.bodies) {
            if (st.id != id) continue;
            const int i = e.count++;
            e.caster_position_m[i] = glm::vec3(to_frame * (st.position_m - receiver_pos));
            e.caster_radius_m[i] = static_cast<float>(scene_.bodies[id].radius_m);
            const auto light = umbra_light_.find(id);
            e.umbra_light[i] = light != umbra_light_.end() ? light->second : glm::vec3(0.0f);
        }
    }
    return e;
}

}  // namespace cupola

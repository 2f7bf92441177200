#pragma once
// Which bodies can shadow which, decided on the CPU in double (Ekelin & Fernqvist 2009,
// sections 3.3.1 and 3.3.3), and the per-receiver description the shaders consume (shading::EclipseCasters).
//   - Static pairs come from the scene's shadow groups: the parent shadows its children, the
//     children shadow the parent, siblings only when the group allows it.
//   - Each frame a pair is kept only while the caster's penumbral cone can reach the
//     receiver's bounding sphere (its atmosphere's top, if any).
#include <glm/glm.hpp>

#include <map>
#include <vector>

#include "config/scene_config.hpp"
#include "shading/shared_shading.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// For every body id: the ids of the casters its shadow groups allow (empty for stars).
std::vector<std::vector<uint16_t>> shadow_candidates(const SceneConfig& scene);

// Radius of the sphere that bounds what a body shows (its atmosphere's top, or its surface).
double shadow_bounding_radius(const BodyConfig& body);

// Can the penumbral cone of the caster (light from a Sun of radius sun_r) reach the sphere
// (receiver, receiver_r)? Cone geometry: at distance x behind the caster along the Sun-caster
// axis the penumbra's radius is r_c + x (r_s + r_c) / |caster - sun|.
bool penumbra_reaches(const glm::dvec3& sun, double sun_r, const glm::dvec3& caster, double caster_r,
                      const glm::dvec3& receiver, double receiver_r);

// The light of a frame: the first star of the snapshot.
struct EclipseSun {
    bool present = false;
    glm::dvec3 position_m{0.0};
    double radius_m = 0.0;
    double limb_u = 0.0;
};
EclipseSun eclipse_sun(const SceneConfig& scene, const Snapshot& snap);

// Per-frame caster selection for every receiver.
class ShadowCasting {
public:
    // umbra_light: light left in each caster's umbra (body id -> rgb); see umbra_light.hpp.
    ShadowCasting(const SceneConfig& scene, std::map<uint16_t, glm::vec3> umbra_light);

    // The casters (nearest the receiver first, at most shading::ECLIPSE_MAX_CASTERS) whose
    // penumbra reaches the receiver now, as shader input: positions relative to the receiver's
    // centre, rotated by `to_frame` (world -> the pass's frame), differences taken in double.
    // count = 0 when nothing can shadow it, when shadows are off, or with no Sun.
    shading::EclipseCasters casters_for(const Snapshot& snap, uint16_t receiver, const glm::dmat3& to_frame) const;

    // Ids only (for tests and logs).
    std::vector<uint16_t> active_casters(const Snapshot& snap, uint16_t receiver) const;

private:
    const SceneConfig& scene_;
    std::vector<std::vector<uint16_t>> candidates_;
    std::map<uint16_t, glm::vec3> umbra_light_;
};

// RenderSettings::flags: the shadow mode in bits 0..2 (ShadowMode).
constexpr uint32_t kShadowModeMask = 0x7u;
static_assert(static_cast<uint32_t>(ShadowMode::Off) <= kShadowModeMask &&
                  static_cast<uint32_t>(ShadowMode::Illustrative) <= kShadowModeMask,
              "every ShadowMode (the shaders' ECLIPSE_MODE_*) must fit in the flags' mode bits");
inline ShadowMode shadow_mode_of(uint32_t flags) { return static_cast<ShadowMode>(flags & kShadowModeMask); }
inline uint32_t with_shadow_mode(uint32_t flags, ShadowMode m) {
    return (flags & ~kShadowModeMask) | static_cast<uint32_t>(m);
}

}  // namespace cupola

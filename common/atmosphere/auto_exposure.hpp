#pragma once
// Cluster-wide automatic exposure. The master decides one exposure per frame from the state every
// channel shares (the snapshot and the scene), so all channels tone-map identically and no seam
// can come from exposure: the mean luminance (scene units) seen over the dome hemisphere, from the
// production atmosphere of every body that has one (sky, lit ground, limb), under the frame's
// eclipse shadows, with the Moon's light on the air where the slaves draw it (moonlit_sky.hpp), evaluated on the CPU by
// the same shared code the slaves run. A pure function of the frame: no temporal adaptation, so snapshots stay
// reproducible from the show alone.
#include <memory>
#include <vector>

#include "atmosphere/moonlit_sky.hpp"
#include "atmosphere/production_model.hpp"
#include "atmosphere/scene_atmospheres.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "eclipse/shadow_casters.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

class AutoExposure {
public:
    // atmospheres: the master's shared models (not owned; must outlive this), or nullptr to
    // build its own when auto exposure is enabled.
    AutoExposure(const ClusterConfig& cluster, const SceneConfig& scene, const SceneAtmospheres* atmospheres = nullptr);
    ~AutoExposure();

    // Mean luminance (scene units) over the channels' ray grid.
    double mean_luminance(const Snapshot& snap) const;
    // The exposure for the frame: fixed, or key / mean luminance clamped to the configured range.
    double exposure(const Snapshot& snap) const;

private:
    // The night sky's second light (atmosphere/moonlit_sky.hpp) as the master estimates it: the
    // brightest body with a measured phase curve, in units of the Sun's irradiance at 1 AU.
    SkySecondLight second_light(const Snapshot& snap, const BodyState& sun) const;
    // The Moon's sky along v (unit, world) in cd/m^2 per unit solar irradiance of the physical spectrum.
    static double moonlit_luminance(const atmosphere::ProductionAtmosphere& model, double d_m, const glm::dvec3& v,
                                    const glm::dvec3& c_hat, const MoonOnAir& moon);
    const ClusterConfig* cluster_;
    const SceneConfig* scene_;
    std::unique_ptr<SceneAtmospheres> own_atmospheres_;
    const SceneAtmospheres* atmospheres_ = nullptr;
    std::unique_ptr<ShadowCasting> casting_;  // eclipse shadows dim the sky the exposure sees
};

}  // namespace cupola

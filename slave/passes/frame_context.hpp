#pragma once
// What every pass sees of one frame: made once per frame from the snapshot by the renderer
// (SceneRenderer, slave/scene_renderer.cpp) before any pass is prepared.
#include <map>
#include <vector>

#include "atmosphere/moonlit_sky.hpp"
#include "config/scene_config.hpp"
#include "passes/channel_view.hpp"
#include "passes/planet_light.hpp"
#include "passes/sphere_billboard.hpp"
#include "shading/shared_shading.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

// The light of the scene: its first BodyKind::Star in the snapshot.
struct SunLight {
    bool present = false;
    glm::dvec3 position_m{0.0};
    double radius_m = 0.0;
    double radiance = 0.0;  // disc centre
    double limb_u = 0.0;
};

// A body of the snapshot as this channel sees it.
struct FrameBody {
    const BodyState* state = nullptr;
    const BodyConfig* body = nullptr;
    SphereView sphere;
    // Its light and whether it shows as a point, a disc or both (a planet or moon without an
    // atmosphere; otherwise the defaults: the disc alone, as drawn).
    PlanetLight light;
};

struct FrameContext {
    const Snapshot* snap = nullptr;
    ChannelView view;
    SunLight light;
    // Every body of the snapshot, farthest first (painter's order; equal distances keep the
    // snapshot's order).
    std::vector<FrameBody> far_to_near;
    // Per planet or moon, the casters whose penumbra reaches it this frame, in the channel frame
    // relative to its centre (eclipse/shadow_casters.hpp).
    std::map<uint16_t, shading::EclipseCasters> casters;
    // The sky is drawn first, and what lies beyond the air after it (slave/passes/beyond_the_air.hpp;
    // decided by AtmospherePass::sky_first): the colour is then not cleared.
    bool sky_first = false;
    // The night sky's second light (passes/moonlight.hpp): the brightest planet or moon at the
    // camera, from the snapshot alone, the same on every channel.
    SkySecondLight moonlight;

    const shading::EclipseCasters& casters_of(uint16_t body) const { return casters.at(body); }
};

}  // namespace cupola

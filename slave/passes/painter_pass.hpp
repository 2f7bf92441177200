#pragma once
// The scene's stars (SunPass) and its planets and moons (BodyPass) as one pass, far to near
// (painter's order), into the colour and the G-buffer. Each disc is opaque and exact in angle,
// so no depth buffer is needed between bodies; a Sun behind a planet is covered by it and a
// planet behind the Sun by the Sun, whatever the order of the scene's bodies. In a frame whose sky
// is drawn first it draws after the atmosphere, each disc taking the air in front of it
// (beyond_the_air.hpp), into the colour alone. A body with terrain near the camera is drawn as
// relief (terrain_drawer.hpp), with a depth test within it.
#include <string>

#include "config/scene_config.hpp"
#include "passes/body_pass.hpp"
#include "passes/eclipse_shadow_uniforms.hpp"
#include "passes/beyond_the_air.hpp"
#include "passes/sun_pass.hpp"
#include "passes/terrain_drawer.hpp"

namespace cupola {

class AtmospherePass;

class PainterPass : public BeyondTheAirPass {
public:
    PainterPass(const SceneConfig& scene, const ClusterConfig& cluster, const EclipseShadowUniforms& shadows);

    std::string name() const override { return "sun and bodies"; }
    PassIo io() const override { return {.writes_color = true, .writes_geometry = true}; }
    int prepare_at(const FrameContext& frame, bool after_sky) override;
    void draw(const PassInputs& in, int step) override;

    // The planets' and moons' drawer, which the glare probe draws the occluders with.
    BodyPass& bodies() { return bodies_; }
    const BodyPass& bodies() const { return bodies_; }
    // The bodies drawn as relief (draws_terrain), instead of their sphere.
    TerrainDrawer& terrain() { return terrain_; }
    const TerrainDrawer& terrain() const { return terrain_; }
    // Bodies whose surface the atmosphere pass draws itself this frame (AtmospherePass::
    // draws_surface) are not drawn here. Set once the atmosphere pass exists (or never).
    void set_surface_drawer(const AtmospherePass* atmosphere) { atmosphere_ = atmosphere; }

private:
    const EclipseShadowUniforms& shadows_;
    SunPass sun_;
    BodyPass bodies_;
    TerrainDrawer terrain_;
    void draw_terrain(const FrameBody& body);
    const FrameContext* frame_ = nullptr;
    const AtmospherePass* atmosphere_ = nullptr;
    bool after_sky_ = false;
};

}  // namespace cupola

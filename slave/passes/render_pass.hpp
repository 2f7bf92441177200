#pragma once
// One step of the render pipeline: SceneRenderer's pass list (slave/scene_renderer.cpp) holds the
// passes in the order they run. Each frame the renderer calls prepare() on every pass in turn and
// then draw() as many times as prepare() asked, binding before each draw the target that the
// pass's declared reads and writes (io()) call for; a pass never binds the frame's targets
// itself. A pass that reads the colour drawn so far and writes colour draws into the other
// colour target (ping-pong, slave/frame_targets.hpp), so no pass samples the texture it draws into.
#include <string>

#include "gl/gl_texture.hpp"
#include "passes/frame_context.hpp"

namespace cupola {

// What a pass reads and writes of the frame's targets. A pass that writes neither colour nor
// G-buffer draws into a target of its own (the glare probe); the frame's are rebound after it.
// A pass that writes the frame's colour or G-buffer binds no other framebuffer.
struct PassIo {
    bool reads_color = false;      // samples the colour drawn so far (PassInputs::color)
    bool reads_geometry = false;   // samples the G-buffer: reflectance and hit distance (PassInputs::geometry)
    bool writes_color = false;     // draws into the colour target (blended or replacing)
    bool writes_geometry = false;  // draws into the G-buffer as well (colour attachment 1 of the scene target)
};

// What one draw samples: set where the pass declares that it reads it, else null.
struct PassInputs {
    const GlTexture* color = nullptr;
    const GlTexture* geometry = nullptr;
};

class RenderPass {
public:
    virtual ~RenderPass() = default;
    virtual std::string name() const = 0;
    virtual PassIo io() const = 0;
    // Takes what the pass needs from the frame (which outlives the frame's draws) and returns
    // how many draws it makes this frame: 0 skips it; the atmosphere makes one per body in view.
    virtual int prepare(const FrameContext& frame) = 0;
    // Draw `step` (0 .. prepare() - 1) into the bound target.
    virtual void draw(const PassInputs& in, int step) = 0;
    // After the frame's glFinish: takes results back from the GPU (occlusion queries).
    virtual void frame_finished() {}
    // Whether the pass samples the G-buffer in this frame (before prepare(); conservative): when
    // no pass does, the frame's G-buffer is not cleared. By default what io() declares.
    virtual bool reads_geometry_in(const FrameContext&) const { return io().reads_geometry; }
};

}  // namespace cupola

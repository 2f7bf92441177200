#pragma once
// Planets' rings (RingConfig; shaders/ring.frag, shared/ring_photometry.glsl): drawn by the body
// pass right after their planet, over it and over whatever lies behind, and read by body.frag
// (BODY_RINGS) for their shadow on the planet. A thin slab of particles in the planet's
// equatorial plane, lit from either face: its light is the sunlight at the planet, not the
// planet's phase curve, times the planet's disc weight (below the point-to-disc handover the rings
// fade with the disc; the point carries the globe's light). In a frame whose sky was drawn first
// (a camera in an atmosphere) they take the air in front of them (beyond_the_air.hpp).
#include <map>
#include <memory>

#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/beyond_the_air.hpp"
#include "passes/frame_context.hpp"
#include "passes/ring_profile.hpp"

namespace cupola {

class RingDrawer {
public:
    explicit RingDrawer(const SceneConfig& scene);  // every ringed planet's map, read and reduced once

    bool has_rings(uint16_t body_id) const { return rings_.count(body_id) != 0; }
    const RingProfile* profile(uint16_t body_id) const;
    // body.frag's BODY_RINGS uniforms (program in use) and the profile bound to kShadowUnit.
    void set_shadow_uniforms(const GlProgram& program, const ChannelView& view, const BodyConfig& body,
                             const BodyState& state) const;
    // The rings of a body that has them, blended over the colour (the G-buffer left as it is);
    // with sky, through the air in front (a frame whose sky was drawn first).
    void draw(const ChannelView& view, const FrameBody& body, const SunLight& sun,
              const SkyInFrontSource* sky = nullptr) const;

    static constexpr unsigned kShadowUnit = 5;

private:
    struct Rings {
        RingProfile profile;
        std::unique_ptr<GlTexture> texture;
    };
    std::map<uint16_t, Rings> rings_;
    std::unique_ptr<GlProgram> program_, after_sky_program_;
    GlEmptyVertexArray vao_;
};

// The planet's north pole (its rings' normal) in the channel frame.
glm::dvec3 ring_normal(const ChannelView& view, const BodyState& state);

// The matrix that maps the channel frame to a body's stretched frame, where its oblate spheroid is
// a sphere of its equatorial radius: B^T diag(1, 1, 1 / (1 - f)) B, B = channel -> body.
glm::dmat3 channel_to_stretched(const ChannelView& view, const BodyConfig& body, const BodyState& state);

}  // namespace cupola

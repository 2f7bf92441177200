#pragma once
// Glare visibility measured where it is rendered (Ekelin & Fernqvist 2009, sections 3.1.1 and
// 3.1.3), in the pass list between the occluders and what does not occlude (occluders -> query ->
// atmosphere -> glare). For each glare source of the
// snapshot whose disc may reach this channel, the probe draws the occluders (the bodies, and a
// body drawn as relief this frame as its relief's tiles; depth only, by true distance) into a
// small view centred on the source, then counts the source's
// disc with two kinds of occlusion query: without depth test (the total) and with it, per wedge
// (the visible part). A direction counts only in the channel that owns it, so the master can sum
// the channels' results. The view is as sharp for a sun of two dome pixels as for one that
// fills the channel, so the fraction does not step as an occluder slides across the disc.
// Queries are read back only once the GPU has them (GL_QUERY_RESULT_AVAILABLE): never a stall;
// a set still running when its slot is needed again is dropped and counted.
#include <memory>
#include <optional>
#include <vector>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "gl/gl_depth_target.hpp"
#include "gl/gl_program.hpp"
#include "passes/body_pass.hpp"
#include "passes/render_pass.hpp"
#include "passes/terrain_drawer.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

struct GlareProbeCounts {
    uint64_t sets_issued = 0;
    uint64_t sets_read = 0;
    uint64_t sets_dropped_late = 0;  // still running when their slot was needed again
};

class GlareProbe : public RenderPass {
public:
    static constexpr int kMaxChannels = 32;       // ownership uniforms in glare_query.frag
    static constexpr double kMinRadius = 2.9e-4;  // a point source is probed as a 1-arcminute disc

    // bodies, shadows: what the occluders are drawn with (the painter pass's).
    GlareProbe(const ClusterConfig& cluster, const ChannelConfig& channel, const SceneConfig& scene, BodyPass& bodies,
               const EclipseShadowUniforms& shadows);
    ~GlareProbe() override;

    // In the pass list: draws into its own depth target, none of the frame's; measures when the
    // snapshot has glare sources and collects after the frame.
    std::string name() const override { return "glare probe"; }
    PassIo io() const override { return {}; }
    int prepare(const FrameContext& frame) override;
    void draw(const PassInputs& in, int step) override;
    void frame_finished() override { collect(); }
    // Off: prepare() draws nothing (the second eye of a stereo frame: measured once per frame).
    void set_measuring(bool on) { measuring_ = on; }

    // Issues the queries for the snapshot's glare sources (after the occluders of the frame's own
    // render, before the atmosphere). Leaves GL with depth test off and depth writes on.
    void measure(const Snapshot& snap, BodyPass& bodies, const SunLight& light, const EclipseShadowUniforms& shadows);
    // Reads every finished query set, oldest first, without waiting. Returns true when a newer
    // measurement became available.
    bool collect();

    // The newest finished measurement (one entry per source this channel saw) and its frame.
    const std::vector<GlareMeasurement>& latest() const { return latest_; }
    std::optional<uint64_t> latest_frame() const { return latest_frame_; }
    // This channel's own visible fraction of a source from the newest measurement (per-channel
    // mode): nothing when the channel did not see it.
    std::optional<float> own_fraction(const GlareSource& source) const;
    const GlareProbeCounts& counts() const { return counts_; }
    // The relief (the painter's terrain drawer): a body drawn as relief this frame occludes as its
    // relief, not as its sphere, so a mountain hides the Sun's glare.
    void set_terrain(TerrainDrawer* terrain) { terrain_ = terrain; }

private:
    struct Set;
    struct View;
    Set& claim_set(uint64_t frame);
    double near_distance_m(const Snapshot& snap, const GlareSource& src) const;
    void draw_occluders(const Snapshot& snap, const GlareSource& src, const View& probe, double source_near_m,
                        BodyPass& bodies, const SunLight& light, const EclipseShadowUniforms& shadows);
    // Draws the body as relief when this frame does (then true).
    bool draw_relief(const BodyState& st, const View& probe);
    void issue_queries(const Snapshot& snap, const GlareSource& src, const View& probe, double source_near_m,
                       const GLuint* queries);
    void read(Set& set);

    int self_ = 0;
    bool own_frustum_only_ = false;
    int size_ = 64;
    std::vector<glm::dmat3> channel_from_camera_;  // per channel of the cluster
    std::vector<glm::vec4> channel_tangents_;
    std::vector<ChannelFrustum> frusta_;
    glm::dmat3 camera_from_dome_;
    const SceneConfig* scene_;
    BodyPass& bodies_;
    const EclipseShadowUniforms& shadows_;
    TerrainDrawer* terrain_ = nullptr;
    bool measuring_ = true;
    const FrameContext* frame_ = nullptr;
    GlDepthTarget target_;
    GlProgram query_;
    GLuint vao_ = 0;
    std::vector<std::unique_ptr<Set>> sets_;
    std::vector<GlareMeasurement> latest_;
    std::optional<uint64_t> latest_frame_;
    GlareProbeCounts counts_;
};

}  // namespace cupola

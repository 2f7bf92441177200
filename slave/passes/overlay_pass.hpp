#pragma once
// The presenter's overlays (common/overlay/): constellation figures, names and boundaries, the
// grids, the horizon and meridian, the cardinal points and the labels of bodies and bright stars,
// drawn last over the frame. Everything is placed on the sky in world or dome coordinates from the
// snapshot alone (overlay_frames.hpp) and sized in dome degrees, so a line or a label that crosses
// the edge between two channels continues in both: a line pixel's coverage is its direction's
// angle to the line's circle (shaders/overlay_line.*), a label is a quad on the sphere textured
// with FreeType's glyphs (passes/text_raster.hpp) from one atlas, mipmapped.
// Colours are display colours: drawn as colour / exposure, they show at the level asked for
// whatever the exposure. Each overlay's opacity is the snapshot's (the master fades it).
// Every overlay's lines are in one buffer and every label in another, each vertex naming its
// overlay (whose frame, colour and width are uniform arrays): a frame draws all the lines in one
// call and the labels in two, and gives the GPU only the arcs that can touch the channel (the runs
// of arcs first, then arc by arc within the runs that do).
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "config/scene_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "overlay/arc_chunks.hpp"
#include "overlay/overlay_frames.hpp"
#include "overlay/overlay_labels.hpp"
#include "passes/render_pass.hpp"

namespace cupola {

class OverlayPass : public RenderPass {
public:
    // Reads the scene's constellation data (throws std::runtime_error naming the file and field)
    // and rasterizes every label once; `stars`: the scene's catalogue (the named stars' labels).
    OverlayPass(const SceneConfig& scene, const std::vector<Star>& stars);

    std::string name() const override { return "overlays"; }
    PassIo io() const override { return {.writes_color = true}; }
    int prepare(const FrameContext& frame) override;
    void draw(const PassInputs& in, int step) override;

    // Line arcs each overlay holds (tests).
    size_t arc_count(OverlayKind k) const { return arcs_[static_cast<size_t>(k)]; }
    // Arcs given to the GPU since the pass was made: only the runs that can touch the channel.
    long arcs_drawn() const { return arcs_drawn_; }
    // Every label, and whether the last frame drew it (label_declutter.hpp: no two overlap).
    const std::vector<OverlayLabel>& labels() const { return labels_; }
    const std::vector<bool>& labels_drawn() const { return label_drawn_; }

private:
    struct LabelBox {             // a label's quad: corners in tangent-plane radians, atlas uv
        glm::vec4 corners{0.0f};  // x0, y0, x1, y1
        glm::vec4 uv{0.0f};       // u0, v0 (bottom), u1, v1 (top)
    };
    void build_lines(const std::vector<ConstellationFigure>& figures);
    void build_labels(const std::vector<ConstellationFigure>& figures, const std::vector<Star>& stars);
    void upload_static_labels();
    void update_body_labels();
    // A label's direction this frame (world frame); none when its overlay is not shown, or for a
    // body's, when the body is the ground or at the camera.
    std::optional<glm::dvec3> label_direction(size_t i) const;
    void declutter();
    // Each overlay's frame and colour this frame, for both programs; false where none is shown.
    bool set_overlay_uniforms();
    // The arcs of a chunk that can touch the channel, as runs of the draw.
    void add_visible_arcs(const ArcChunk& c, const glm::mat3& to_channel, const FrustumSides& sides);
    void draw_lines();
    void draw_labels();
    glm::vec4 color_of(size_t k) const;
    static std::vector<float> label_vertices(const LabelBox& box, const glm::dvec3& anchor, size_t kind);

    const SceneConfig* scene_;
    GlProgram line_program_, label_program_;
    std::unique_ptr<GlVertexBuffer> lines_;  // every overlay's arcs, one after the other
    std::array<size_t, kOverlayCount> arcs_{};
    std::array<std::vector<ArcChunk>, kOverlayCount> chunks_;  // first_arc: in lines_
    std::vector<glm::vec4> arc_cones_;                         // every arc's (overlay frame), as in lines_
    std::array<bool, kOverlayCount> shown_{};                  // this frame: visible, with its frame
    std::array<glm::mat3, kOverlayCount> to_channel_{};        // this frame: overlay frame -> channel
    std::vector<const void*> offsets_;                         // byte offsets into the line buffer's indices
    size_t next_index_ = 0;
    std::vector<GLsizei> counts_;
    long arcs_drawn_ = 0;
    std::vector<OverlayLabel> labels_;
    std::vector<LabelBox> boxes_;  // one per label
    std::unique_ptr<GlTexture> atlas_;
    GlVertexBuffer static_labels_;                       // every label but the bodies', in label order
    std::vector<GLint> label_vertex_first_;              // per label: its first vertex there (-1: a body's)
    std::vector<bool> label_drawn_;                      // per label, this frame
    std::vector<std::optional<glm::dvec3>> label_dirs_;  // per label, this frame (none: not shown)
    std::vector<GLint> run_first_;                       // this frame's runs of drawn labels in static_labels_
    std::vector<GLsizei> run_count_;
    GlVertexBuffer body_labels_;
    const FrameContext* frame_ = nullptr;
    OverlayFrames frames_;
    float pixel_rad_ = 0.0f;
};

}  // namespace cupola

#pragma once
// The alignment patterns a technician aligns projectors with (docs/ALIGNMENT.md), in the channel
// render: when the snapshot's settings ask for one (AlignmentPattern in settings.flags) this pass
// replaces the scene's colour, and the renderer skips the scene's passes before it
// (slave/scene_renderer.cpp), so the pattern goes through whatever follows it in the list (the
// projector's warp and blend). Patterns:
//   grid   azimuth/elevation lines in the dome frame (shaders/shared/alignment_grid.glsl); the
//          directions that another channel's frustum also covers tinted (each other channel's
//          rotation and tangents are uniforms: ChannelFrustum::contains per pixel); the channel's
//          name and id as text (FreeType, rasterized once here: passes/text_raster.hpp);
//   white  a uniform field of 1 (after exposure), for blend checks;
//   black  a field of 0, for the black level.
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "config/cluster_config.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "passes/render_pass.hpp"
#include "passes/text_raster.hpp"

namespace cupola {

class PatternPass : public RenderPass {
public:
    static constexpr int kMaxOtherChannels = 16;  // shaders/pattern.frag's MAX_OTHER_CHANNELS

    // The channel drawn and the cluster it belongs to (its other channels give the overlaps; past
    // kMaxOtherChannels they are not tinted). Throws std::runtime_error when the font cannot be read.
    PatternPass(const ClusterConfig& cluster, const ChannelConfig& channel,
                const std::string& font_file = kDefaultFontFile);

    std::string name() const override { return "alignment pattern"; }
    PassIo io() const override { return {.writes_color = true}; }
    // One draw when the snapshot asks for a pattern, none otherwise.
    int prepare(const FrameContext& frame) override;
    void draw(const PassInputs& in, int step) override;

    // The label's text ("<name> #<id>") and where it is drawn: window pixels, origin at the
    // bottom left, (x0, y0, x1, y1), centred in the channel.
    const std::string& label() const { return label_; }
    glm::vec4 label_box() const { return label_box_; }
    // The tint of directions another channel also covers (linear, after exposure).
    static glm::vec3 overlap_tint() { return {0.0f, 0.05f, 0.12f}; }

private:
    static std::vector<glm::vec4> label_texels(const TextRaster& text);
    void set_channel_uniforms() const;

    std::string label_;
    TextRaster text_;
    glm::vec4 label_box_{0.0f};
    glm::vec4 tangents_;
    glm::vec2 size_;
    glm::mat3 channel_to_dome_;
    std::vector<glm::mat3> other_dome_to_channel_;
    std::vector<glm::vec4> other_tangents_;
    GlTexture label_texture_;
    GlProgram program_;
    GlEmptyVertexArray vao_;
    const FrameContext* frame_ = nullptr;
};

}  // namespace cupola

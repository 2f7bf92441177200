#include "passes/pattern_pass.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "projection/channel_frustum.hpp"

namespace cupola {

namespace {

std::string channel_label(const ChannelConfig& ch) { return ch.name + " #" + std::to_string(ch.id); }

// The em height of the label: a sixteenth of the channel's height, at least 12 pixels.
int label_pixel_size(const ChannelConfig& ch) { return std::clamp(ch.height / 16, 12, 256); }

glm::vec4 frustum_tangents(const ChannelFrustum& f) {
    return glm::vec4(f.tan_left(), f.tan_right(), f.tan_down(), f.tan_up());
}

}  // namespace

std::vector<glm::vec4> PatternPass::label_texels(const TextRaster& text) {
    std::vector<glm::vec4> out(text.coverage.size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec4(text.coverage[i], 0.0f, 0.0f, 1.0f);
    return out;
}

PatternPass::PatternPass(const ClusterConfig& cluster, const ChannelConfig& channel, const std::string& font_file)
    : label_(channel_label(channel)),
      text_(rasterize_text(label_, label_pixel_size(channel), font_file)),
      label_texture_(text_.width, text_.height, label_texels(text_).data(), GL_LINEAR),
      program_("fullscreen.vert", "pattern.frag") {
    const ChannelFrustum own = channel.frustum();
    tangents_ = frustum_tangents(own);
    size_ = glm::vec2(channel.width, channel.height);
    channel_to_dome_ = glm::mat3(own.rotation());
    // The label, one texel per pixel, centred (a wider label than the channel is squeezed).
    const float w = std::min(static_cast<float>(text_.width), 0.9f * size_.x), h = static_cast<float>(text_.height);
    label_box_ = glm::vec4(std::floor(0.5f * (size_.x - w)), std::floor(0.5f * (size_.y - h)), 0.0f, 0.0f);
    label_box_.z = label_box_.x + w;
    label_box_.w = label_box_.y + h;
    for (const ChannelConfig& other : cluster.channels) {
        if (other.id == channel.id) continue;
        if (static_cast<int>(other_tangents_.size()) == kMaxOtherChannels) {
            spdlog::warn("alignment pattern: channel {} tints the overlaps of its first {} other channels only", label_,
                         kMaxOtherChannels);
            break;
        }
        const ChannelFrustum f = other.frustum();
        other_dome_to_channel_.push_back(glm::mat3(glm::transpose(f.rotation())));
        other_tangents_.push_back(frustum_tangents(f));
    }
}

int PatternPass::prepare(const FrameContext& frame) {
    frame_ = &frame;
    return alignment_pattern_of(frame.snap->settings.flags) == AlignmentPattern::Off ? 0 : 1;
}

void PatternPass::set_channel_uniforms() const {
    program_.set("u_tangents", tangents_);
    program_.set("u_size", size_);
    program_.set("u_channel_to_dome", channel_to_dome_);
    const int others = static_cast<int>(other_tangents_.size());
    program_.set("u_other_count", others);
    if (others > 0) {
        program_.set("u_other_dome_to_channel", other_dome_to_channel_.data(), others);
        program_.set("u_other_tangents", other_tangents_.data(), others);
    }
    program_.set("u_overlap_tint", overlap_tint());
    program_.set("u_label_box", label_box_);
    program_.set("u_label_color", glm::vec3(1.0f, 1.0f, 1.0f));
    program_.set("u_label", 0);
}

void PatternPass::draw(const PassInputs&, int) {
    const RenderSettings& s = frame_->snap->settings;
    program_.use();
    program_.set("u_pattern", static_cast<int>(alignment_pattern_of(s.flags)));
    program_.set("u_inv_exposure", 1.0f / s.exposure);
    set_channel_uniforms();
    label_texture_.bind(0);
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gl::check("alignment pattern pass");
}

}  // namespace cupola

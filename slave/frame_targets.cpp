#include "frame_targets.hpp"

#include <stdexcept>

namespace cupola {

FrameTargets::FrameTargets(int width, int height, bool depth)
    : color_a_(width, height, nullptr, GL_NEAREST),
      color_b_(width, height, nullptr, GL_NEAREST),
      geometry_(width, height, nullptr, GL_NEAREST),
      scene_({&color_a_, &geometry_}),
      a_({&color_a_}),
      b_({&color_b_}) {
    if (depth) scene_.add_depth();
}

void FrameTargets::begin_frame(bool geometry, bool color) {
    current_ = &a_;
    scene_.bind();
    bound_ = &scene_;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (color) {
        scene_.clear(0, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        ++color_clears_;
    }
    if (scene_.has_depth()) scene_.clear_depth();  // the terrain's
    if (!geometry) return;
    scene_.clear(1, glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));  // distance < 0: no geometry
    ++geometry_clears_;
}

PassInputs FrameTargets::bind_for(const PassIo& io) {
    const GlFramebuffer* target = nullptr;
    if (io.writes_geometry) {
        if (current_ != &a_)
            throw std::logic_error(
                "frame targets: a pass writes the G-buffer after the colour moved to the second target");
        target = &scene_;
    } else if (io.writes_color) {
        target = io.reads_color ? &other() : current_;
    }
    if (target != bound_ && target) target->bind();
    bound_ = target;  // null: the pass binds a target of its own
    PassInputs in;
    if (io.reads_color) in.color = &current_->color(0);
    if (io.reads_geometry) in.geometry = &geometry_;
    return in;
}

void FrameTargets::drawn(const PassIo& io) {
    if (io.reads_color && io.writes_color) current_ = &other();
}

Image FrameTargets::read() const { return current_->read(); }

void FrameTargets::check_order(const std::vector<std::unique_ptr<RenderPass>>& passes) {
    const RenderPass* color_reader = nullptr;
    for (const auto& p : passes) {
        const PassIo io = p->io();
        if (io.writes_geometry && (io.reads_geometry || io.reads_color))
            throw std::logic_error("render pass \"" + p->name() +
                                   "\" writes the G-buffer and reads the colour or the G-buffer: it would sample "
                                   "what it draws into");
        if (io.writes_geometry && color_reader)
            throw std::logic_error("render pass \"" + p->name() + "\" writes the G-buffer after \"" +
                                   color_reader->name() +
                                   "\" read the colour: the G-buffer is attached with the first colour target only");
        if (io.reads_color && io.writes_color && !color_reader) color_reader = p.get();
    }
}

}  // namespace cupola

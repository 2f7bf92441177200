#pragma once
// One frame as the output stage's sinks see it: the channel render and, when the warp pass ran,
// the projector frame it made. The synchronous reads here are counted (ProjectorOutput::read_backs,
// with the files sink's asynchronous ones), so that a slave whose sinks need no pixels on the CPU
// provably reads none.
#include <cstdint>

#include "image/frame_image.hpp"
#include "gl/gl_texture.hpp"
#include "output/warp_pass.hpp"
#include "scene_renderer.hpp"

namespace cupola {

class ProjectorFrame {
public:
    ProjectorFrame(SceneRenderer& channel, const WarpPass* warp, FrameMetadata meta, double exposure,
                   uint64_t& warp_read_backs)
        : channel_(channel), warp_(warp), meta_(std::move(meta)), exposure_(exposure), read_backs_(warp_read_backs) {}

    const FrameMetadata& meta() const { return meta_; }
    double exposure() const { return exposure_; }
    // True when the warp pass ran: the projector frame is in its targets. False: files only and
    // no calibration, so the frame files are the channel render as it always was.
    bool warped() const { return warp_ != nullptr; }

    // The channel render, linear, before exposure, row 0 at the top.
    Image read_channel() const { return channel_.read_back(); }
    // The projector frame, linear light times exposure (after the blend), row 0 at the top.
    Image read_linear() const;
    // The projector frame encoded for the projector (the bytes live sinks show), row 0 at the top.
    EncodedImage read_encoded() const;
    // What live sinks blit to their surface: the warp pass's encoded RGBA8 framebuffer (GL row 0
    // at the bottom) and its size; warped() only.
    unsigned encoded_framebuffer() const { return warp().encoded_framebuffer(); }
    // The GL textures behind the reads above, for asynchronous read-backs (slave/output/files_sink):
    // the channel render (RGBA32F), and, warped() only, the projector frame's linear (RGBA32F) and
    // encoded (RGBA8) targets; GL row 0 at the bottom.
    unsigned channel_texture() const { return channel_.color().id(); }
    int channel_width() const { return channel_.color().width(); }
    int channel_height() const { return channel_.color().height(); }
    unsigned linear_texture() const { return warp().linear_texture(); }
    unsigned encoded_texture() const { return warp().encoded_texture(); }
    int width() const { return warp().width(); }
    int height() const { return warp().height(); }

private:
    const WarpPass& warp() const;

    SceneRenderer& channel_;
    const WarpPass* warp_;
    FrameMetadata meta_;
    double exposure_;
    uint64_t& read_backs_;
};

}  // namespace cupola

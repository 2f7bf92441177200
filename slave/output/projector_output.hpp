#pragma once
// The slave's output stage: from the channel's final colour texture to every sink of the channel
// (output.sink). Per frame, two phases:
//  1. take(): the warp pass runs when a calibration is given or a live sink needs the encoded
//     projector frame; then every sink takes the frame (the files sink queues it for writing,
//     live sinks blit it into their back buffer). Nothing is read back unless a sink asks:
//     window or KMS alone read nothing; the files sink reads asynchronously (pixel buffers).
//  2. present(): every live sink swaps (FramePresenter), at the swap lock's "present N".
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "calibration/projector_warp.hpp"
#include "config/cluster_config.hpp"
#include "output/files_sink.hpp"
#include "output/frame_presenter.hpp"
#include "output/output_sink.hpp"
#include "output/output_surface.hpp"
#include "output/warp_pass.hpp"
#include "scene_renderer.hpp"

namespace cupola {

struct FilesOutput {
    std::string dir;
    std::vector<std::string> formats;
};

class ProjectorOutput : public FramePresenter {
public:
    // The sinks named in `sinks`, on `surface` (whose context is current); files go to `files`.
    // content_*: the channel render's size; warp: the projector's calibration, if any;
    // content_view: the channel's frustum, for the eye's acuity blur at night (none: no blur).
    ProjectorOutput(OutputSurface& surface, const SinkConfig& sinks, FilesOutput files,
                    std::optional<ProjectorWarp> warp, int content_width, int content_height,
                    std::optional<ChannelFrustum> content_view = std::nullopt);
    ~ProjectorOutput() override;

    // Phase 1 for the frame the renderer last drew. Returns the milliseconds the files sink
    // waited for room in its queue (0 without one).
    double take(SceneRenderer& channel, const FrameMetadata& meta, double exposure);
    // Phase 2: swaps every live sink; CLOCK_MONOTONIC ns just after.
    uint64_t present(uint64_t frame) override;
    bool has_live_output() const override { return live_; }
    // Every frame taken is on disk (or counted failed): the files sink's pending read-backs are
    // collected and written. Returns the milliseconds it waited (0 without a files sink).
    double settle();
    // Waits until every frame taken is done; returns the frames that failed (not written).
    uint64_t finish();

    std::vector<std::string> sink_names() const;
    // Read-backs of the output stage: the files sink's (asynchronous, of the channel render or
    // the warp pass's targets) and any synchronous one through ProjectorFrame. SceneRenderer's own
    // read_back() (render()) counts in SceneRenderer::read_backs(). Window and KMS read nothing.
    uint64_t read_backs() const { return read_backs_ + (files_ ? files_->read_backs() : 0); }
    uint64_t presents() const { return presents_; }
    bool warps() const { return warp_ != nullptr; }

private:
    std::unique_ptr<WarpPass> warp_;  // null: files only and no calibration
    std::vector<std::unique_ptr<OutputSink>> sinks_;
    FilesSink* files_ = nullptr;
    bool live_ = false;
    uint64_t read_backs_ = 0;
    uint64_t presents_ = 0;
};

}  // namespace cupola

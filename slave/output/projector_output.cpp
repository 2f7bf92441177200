#include "output/projector_output.hpp"

#include <stdexcept>

#include "gl/gl_texture.hpp"
#include "output/kms_sink.hpp"
#include "output/window_sink.hpp"
#include "util/monotonic_clock.hpp"

namespace cupola {

ProjectorOutput::ProjectorOutput(OutputSurface& surface, const SinkConfig& sinks, FilesOutput files,
                                 std::optional<ProjectorWarp> warp, int content_width, int content_height,
                                 std::optional<ChannelFrustum> content_view) {
    for (const std::string& name : sinks.sinks) {
        if (name == "files") {
            auto f = std::make_unique<FilesSink>(files.dir, files.formats);
            files_ = f.get();
            sinks_.push_back(std::move(f));
        } else if (name == "window") {
            if (!surface.window()) throw std::logic_error("output.sink window: the GL context has no X11 window");
            sinks_.push_back(std::make_unique<WindowSink>(surface.egl(), *surface.window()));
        } else if (name == "kms") {
            if (!surface.kms()) throw std::logic_error("output.sink kms: the GL context has no KMS output");
            sinks_.push_back(std::make_unique<KmsSink>(surface.egl(), *surface.kms()));
        } else {
            throw std::invalid_argument("output.sink: \"" + name + "\" is not a sink (files, window, kms)");
        }
        live_ = live_ || sinks_.back()->live();
    }
    WarpOptions options;
    options.content_view = std::move(content_view);
    if (warp || live_) warp_ = std::make_unique<WarpPass>(std::move(warp), content_width, content_height, options);
}

ProjectorOutput::~ProjectorOutput() { finish(); }

double ProjectorOutput::take(SceneRenderer& channel, const FrameMetadata& meta, double exposure) {
    if (warp_)
        warp_->draw(channel.color().id(), exposure, meta.tone_white, meta.night_adapted_cd_m2(),
                    meta.acuity_sigma_rad());
    const ProjectorFrame frame(channel, warp_.get(), meta, exposure, read_backs_);
    for (const auto& sink : sinks_) sink->take(frame);
    return files_ ? files_->last_wait_ms() : 0.0;
}

uint64_t ProjectorOutput::present(uint64_t) {
    for (const auto& sink : sinks_)
        if (sink->live()) sink->present();
    if (live_) ++presents_;
    return monotonic_ns();
}

double ProjectorOutput::settle() { return files_ ? files_->settle() : 0.0; }

uint64_t ProjectorOutput::finish() {
    uint64_t failed = 0;
    for (const auto& sink : sinks_) failed += sink->finish();
    return failed;
}

std::vector<std::string> ProjectorOutput::sink_names() const {
    std::vector<std::string> out;
    for (const auto& s : sinks_) out.push_back(s->name());
    return out;
}

}  // namespace cupola

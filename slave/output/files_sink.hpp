#pragma once
// The files sink: DIR/frame_NNNNNN.{png,exr}, written on the frame writer's thread
// (slave/async_frame_writer). With no warp pass run (files only, no calibration) the files are the
// channel render, exactly as ever: EXR linear x exposure, PNG sRGB encoded on the CPU. When the
// warp pass ran, they are the projector frame: the EXR its linear target, the PNG its encoded
// bytes, so that the PNG holds exactly what a window or KMS output shows.
#include <string>
#include <vector>

#include "async_frame_writer.hpp"
#include "output/output_sink.hpp"

namespace cupola {

class FilesSink : public OutputSink {
public:
    FilesSink(std::string dir, std::vector<std::string> formats);
    std::string name() const override { return "files"; }
    bool live() const override { return false; }
    void take(const ProjectorFrame& frame) override;
    uint64_t finish() override;
    // Milliseconds the last take() waited for room in the writer's queue.
    double last_wait_ms() const { return last_wait_ms_; }
    uint64_t written() const { return writer_.written(); }

private:
    bool wants(const std::string& format) const;

    std::vector<std::string> formats_;
    AsyncFrameWriter writer_;
    double last_wait_ms_ = 0.0;
};

}  // namespace cupola

#pragma once
// The files sink: DIR/frame_NNNNNN.{png,exr}, written on the frame writer's thread
// (slave/async_frame_writer). With no warp pass run (files only, no calibration) the files are the
// channel render, exactly as ever: EXR linear x exposure, PNG encoded on the CPU (gamut map, sRGB:
// common/image/frame_image.hpp). When the warp pass ran, they are the projector frame: the EXR its
// linear target, the PNG its encoded bytes, so that the PNG holds exactly what a window or KMS
// output shows.
//
// The pixels come back asynchronously (slave/output/pbo_readback): take() only queues the
// frame's reads into pixel buffer objects; the frame is copied out and handed to the writer
// later, when its buffers are needed again by a newer frame or at settle(), so the next frame's
// rendering never waits on a read-back. Each read is in the precision and channels its file
// stores: the EXR is RGBA 32-bit float (physical units span ~1e-6 to ~2e9 cd/m^2, beyond half
// floats; alpha is stored), so its read is RGBA float; a projector PNG stores the warp pass's
// encoded RGBA8 bytes, so its read is RGBA8 (a quarter of the float read); a channel PNG is
// exposed, gamut-mapped and encoded on the CPU from the float render (the exposure is applied
// there, so the read must hold the render's full range), which the EXR shares when both are
// written. Frames reach the writer in the order they were taken; a frame that cannot be read
// back is logged and counted as failed, never dropped silently.
#include <deque>
#include <string>
#include <vector>

#include "async_frame_writer.hpp"
#include "output/output_sink.hpp"
#include "output/pbo_readback.hpp"

namespace cupola {

class FilesSink : public OutputSink {
public:
    // frames_in_flight: how many taken frames may wait for their read-back at once (>= 1).
    FilesSink(std::string dir, std::vector<std::string> formats, size_t frames_in_flight = 2);
    ~FilesSink() override;
    std::string name() const override { return "files"; }
    bool live() const override { return false; }
    // Queues the frame's read-backs; hands the oldest frames to the writer first when their
    // buffers are needed.
    void take(const ProjectorFrame& frame) override;
    // Every frame taken is read back and written (or counted as failed). Returns the
    // milliseconds it waited.
    double settle();
    uint64_t finish() override;
    // Milliseconds the last take() waited (for older read-backs and room in the writer's queue).
    double last_wait_ms() const { return last_wait_ms_; }
    uint64_t written() const { return writer_.written(); }
    std::vector<uint64_t> written_frames() const { return writer_.written_frames(); }
    // Reads queued into pixel buffers since construction (one or two per frame).
    uint64_t read_backs() const { return reads_.reads_started(); }
    // Frames taken whose pixels are still in pixel buffers.
    size_t frames_pending() const { return pending_.size(); }

private:
    struct Pending {
        FrameMetadata meta;
        double exposure = 1.0;
        bool warped = false;
        bool linear = false, encoded = false;  // which reads were queued, in this order
        int width = 0, height = 0;
    };
    bool wants(const std::string& format) const;
    // The oldest pending frame: its reads collected, handed to the writer.
    void deliver_oldest();
    void submit(const Pending& p);

    std::vector<std::string> formats_;
    AsyncFrameWriter writer_;
    PboReadback reads_;
    std::deque<Pending> pending_;
    size_t max_frames_;
    double last_wait_ms_ = 0.0;
    uint64_t failed_reads_ = 0;
};

}  // namespace cupola

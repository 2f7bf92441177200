#pragma once
// One place a channel's frames go (output.sink): frame files, an X11 window, a KMS output.
// The output stage (projector_output.hpp) hands every sink the frame once it is drawn (take),
// then, on "present N", tells the live ones to show it (present). Several sinks run at once.
#include <cstdint>
#include <string>

#include "output/projector_frame.hpp"

namespace cupola {

class OutputSink {
public:
    virtual ~OutputSink() = default;
    virtual std::string name() const = 0;
    // A live sink shows frames: it needs the warp pass's encoded target and swaps on present().
    virtual bool live() const = 0;
    // The frame is drawn: a live sink draws it into its back buffer, the files sink queues it.
    virtual void take(const ProjectorFrame& frame) = 0;
    // Shows the frame last taken (eglSwapBuffers, a page flip); files: nothing.
    virtual void present() {}
    // Waits until what was taken is done (files on disk); returns how many frames failed.
    virtual uint64_t finish() { return 0; }
};

}  // namespace cupola

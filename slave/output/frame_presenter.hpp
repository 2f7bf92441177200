#pragma once
// The second phase of a frame: showing what was rendered. A slave renders and warps frame N into
// its output stage and reports "ready N"; it shows the frame only when told "present N" (the swap
// lock, master/). present() is that moment: it swaps every live output (eglSwapBuffers on a
// window, a page flip on KMS) and returns the CLOCK_MONOTONIC time just after the swap, in ns,
// for the master's skew statistics. Everything expensive (render, warp, read-back, encoding) is
// done before present() is called, so the present itself is short.
#include <cstdint>

namespace cupola {

class FramePresenter {
public:
    virtual ~FramePresenter() = default;
    // Shows the frame that was last prepared (frame number `frame`) on every live output.
    // Returns CLOCK_MONOTONIC ns taken just after the swap (or just now when nothing is live).
    virtual uint64_t present(uint64_t frame) = 0;
    // False when no output shows anything (files only): present() then only timestamps.
    virtual bool has_live_output() const = 0;
};

}  // namespace cupola

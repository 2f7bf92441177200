#include "output/kms_sink.hpp"

#include "output/window_sink.hpp"

namespace cupola {

void KmsSink::take(const ProjectorFrame& frame) {
    blit_to_default_framebuffer(frame, display_.width(), display_.height());
}

// The page flip itself waits for the vertical blank: no swap interval is involved.
void KmsSink::present() {
    egl_.swap_buffers();
    display_.flip();
}

}  // namespace cupola

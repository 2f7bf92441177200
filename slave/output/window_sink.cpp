#include "output/window_sink.hpp"

#include <spdlog/spdlog.h>

namespace cupola {

void blit_to_default_framebuffer(const EncodedTarget& target, int width, int height) {
    target.bind();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glDisable(GL_FRAMEBUFFER_SRGB);  // the bytes are encoded already: copied, not converted
    const bool same = target.width() == width && target.height() == height;
    glBlitFramebuffer(0, 0, target.width(), target.height(), 0, 0, width, height, GL_COLOR_BUFFER_BIT,
                      same ? GL_NEAREST : GL_LINEAR);
    gl::check("blit of the projector frame to the output surface");
    glFlush();  // the copy runs now, so that present() is only the swap
}

WindowSink::WindowSink(EglContext& egl, const X11Window& window) : egl_(egl), rect_(window.rect()) {
    egl_.set_swap_interval(1);
}

void WindowSink::take(const ProjectorFrame& frame) {
    const EncodedTarget& t = frame.encoded_target();
    if ((t.width() != rect_.width || t.height() != rect_.height) && frame.meta().frame % 600 == 0)
        spdlog::warn("window sink: the projector frame is {}x{} but the window {}x{}: scaled", t.width(), t.height(),
                     rect_.width, rect_.height);
    blit_to_default_framebuffer(t, rect_.width, rect_.height);
}

}  // namespace cupola

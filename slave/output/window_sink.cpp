#include "output/window_sink.hpp"

#include <spdlog/spdlog.h>

#include "gl/gl_api.hpp"

namespace cupola {

void blit_to_default_framebuffer(const ProjectorFrame& frame, int width, int height) {
    glDisable(GL_FRAMEBUFFER_SRGB);  // the bytes are encoded already: copied, not converted
    const bool same = frame.width() == width && frame.height() == height;
    glBlitNamedFramebuffer(frame.encoded_framebuffer(), 0, 0, 0, frame.width(), frame.height(), 0, 0, width, height,
                           GL_COLOR_BUFFER_BIT, same ? GL_NEAREST : GL_LINEAR);
    gl::check("blit of the projector frame to the output surface");
    glFlush();  // the copy runs now, so that present() is only the swap
}

WindowSink::WindowSink(EglContext& egl, const X11Window& window) : egl_(egl), rect_(window.rect()) {
    egl_.set_swap_interval(1);
}

void WindowSink::take(const ProjectorFrame& frame) {
    if ((frame.width() != rect_.width || frame.height() != rect_.height) && frame.meta().frame % 600 == 0)
        spdlog::warn("window sink: the projector frame is {}x{} but the window {}x{}: scaled", frame.width(),
                     frame.height(), rect_.width, rect_.height);
    blit_to_default_framebuffer(frame, rect_.width, rect_.height);
}

}  // namespace cupola

#pragma once
// The window sink: the projector frame (the warp pass's encoded RGBA8 target) blitted into the
// back buffer of an X11 window (x11_window.hpp) through EGL, shown by eglSwapBuffers on present,
// one frame per vertical blank (swap interval 1).
#include "gl/egl_context.hpp"
#include "output/output_sink.hpp"
#include "output/x11_window.hpp"

namespace cupola {

class WindowSink : public OutputSink {
public:
    // egl: current, with a window surface on `window`.
    WindowSink(EglContext& egl, const X11Window& window);
    std::string name() const override { return "window"; }
    bool live() const override { return true; }
    void take(const ProjectorFrame& frame) override;
    void present() override { egl_.swap_buffers(); }

private:
    EglContext& egl_;
    ScreenRect rect_;
};

// Draws the frame's encoded framebuffer over the whole default framebuffer (width x height): a
// copy when the sizes agree, else linear scaling. Shared by the window and KMS sinks.
void blit_to_default_framebuffer(const ProjectorFrame& frame, int width, int height);

}  // namespace cupola

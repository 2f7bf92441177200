#pragma once
// The window a window sink draws into: on an X11 display, covering a RandR output (or the whole
// screen), without decorations (Motif WM hints, and override-redirect when fullscreen, so no
// window manager moves or frames it) and without a cursor (an invisible one).
// Xlib's types stay in x11_window.cpp: its macros (None, Bool, Status) would leak everywhere.
#include <cstdint>
#include <string>

#include "config/cluster_config.hpp"
#include "image/frame_image.hpp"

namespace cupola {

struct ScreenRect {
    int x = 0, y = 0, width = 0, height = 0;
};

class X11Window {
public:
    // Opens config.display and maps the window: the geometry of config.output_name when
    // fullscreen (the whole screen when no output is named), else raster_width x raster_height at
    // that output's top left. Throws naming the output.window field that was wrong.
    X11Window(const WindowOutputConfig& config, int raster_width, int raster_height);
    ~X11Window();
    X11Window(const X11Window&) = delete;
    X11Window& operator=(const X11Window&) = delete;

    void* native_display() const { return display_; }  // Display*
    void* native_window() { return &window_; }         // a pointer to the Window, as EGL's X11 platform takes it
    uint32_t visual_id() const { return visual_id_; }
    const ScreenRect& rect() const { return rect_; }
    // What the window shows now (XGetImage), row 0 at the top, alpha 255.
    EncodedImage read_pixels() const;

private:
    void* display_ = nullptr;
    unsigned long window_ = 0;
    unsigned long cursor_ = 0;
    uint32_t visual_id_ = 0;
    ScreenRect rect_;
};

// The geometry of a RandR output on the display's default screen ("" : the whole screen).
// Throws naming output.window.output_name and listing the outputs when there is no such one.
ScreenRect x11_output_rect(void* display, const std::string& output_name);

}  // namespace cupola

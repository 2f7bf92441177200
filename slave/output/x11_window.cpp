#include "output/x11_window.hpp"

#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/Xrandr.h>
#include <spdlog/spdlog.h>

#include <stdexcept>

#include <unistd.h>

namespace cupola {

namespace {

// Xlib's default handler exits the process on any protocol error; this one logs it, and the call
// that failed reports failure to its caller.
int log_x_error(Display* dpy, XErrorEvent* e) {
    char text[256] = {};
    XGetErrorText(dpy, e->error_code, text, sizeof text);
    spdlog::error("X11: {} (request {}.{})", text, static_cast<int>(e->request_code), static_cast<int>(e->minor_code));
    return 0;
}

std::string randr_outputs(Display* dpy, XRRScreenResources* res, const std::string& wanted, ScreenRect* found) {
    std::string names;
    for (int i = 0; i < res->noutput; ++i) {
        XRROutputInfo* out = XRRGetOutputInfo(dpy, res, res->outputs[i]);
        if (!out) continue;
        const std::string name(out->name, static_cast<size_t>(out->nameLen));
        names += (names.empty() ? "" : ", ") + name;
        if (name == wanted && out->crtc) {
            if (XRRCrtcInfo* crtc = XRRGetCrtcInfo(dpy, res, out->crtc)) {
                *found = {crtc->x, crtc->y, static_cast<int>(crtc->width), static_cast<int>(crtc->height)};
                XRRFreeCrtcInfo(crtc);
            }
        }
        XRRFreeOutputInfo(out);
    }
    return names;
}

// Motif window-manager hints (the de facto standard every X11 window manager reads): flags =
// MWM_HINTS_DECORATIONS, decorations = none.
void remove_decorations(Display* dpy, Window w) {
    const long hints[5] = {2, 0, 0, 0, 0};
    const Atom motif = XInternAtom(dpy, "_MOTIF_WM_HINTS", False);
    XChangeProperty(dpy, w, motif, motif, 32, PropModeReplace, reinterpret_cast<const unsigned char*>(hints), 5);
}

Cursor invisible_cursor(Display* dpy, Window w) {
    const char empty[1] = {0};
    const Pixmap bitmap = XCreateBitmapFromData(dpy, w, empty, 1, 1);
    XColor black{};
    const Cursor c = XCreatePixmapCursor(dpy, bitmap, bitmap, &black, &black, 0, 0);
    XFreePixmap(dpy, bitmap);
    return c;
}

void wait_mapped(Display* dpy, Window w) {
    XEvent ev;
    do XWindowEvent(dpy, w, StructureNotifyMask, &ev);
    while (ev.type != MapNotify);
}

// A display server that is starting (a node booting into its channel) or busy may refuse a
// connection for a moment: try for up to 2 s.
Display* open_display(const std::string& name) {
    for (int attempt = 0; attempt < 20; ++attempt) {
        if (Display* dpy = XOpenDisplay(name.c_str())) return dpy;
        ::usleep(100000);
    }
    return nullptr;
}

int mask_shift(unsigned long mask) {
    int s = 0;
    while (mask && !(mask & 1)) {
        mask >>= 1;
        ++s;
    }
    return s;
}

}  // namespace

ScreenRect x11_output_rect(void* display, const std::string& output_name) {
    auto* dpy = static_cast<Display*>(display);
    const int screen = DefaultScreen(dpy);
    if (output_name.empty()) return {0, 0, DisplayWidth(dpy, screen), DisplayHeight(dpy, screen)};
    int event_base = 0, error_base = 0;
    if (!XRRQueryExtension(dpy, &event_base, &error_base))
        throw std::runtime_error("output.window.output_name \"" + output_name +
                                 "\": the X11 display has no RandR extension to name outputs by");
    XRRScreenResources* res = XRRGetScreenResourcesCurrent(dpy, RootWindow(dpy, screen));
    if (!res) throw std::runtime_error("output.window.output_name: RandR gives no screen resources");
    ScreenRect found;
    const std::string names = randr_outputs(dpy, res, output_name, &found);
    XRRFreeScreenResources(res);
    if (found.width <= 0)
        throw std::runtime_error("output.window.output_name \"" + output_name +
                                 "\": no such active RandR output (outputs: " + (names.empty() ? "none" : names) + ")");
    return found;
}

X11Window::X11Window(const WindowOutputConfig& config, int raster_width, int raster_height) {
    XSetErrorHandler(log_x_error);
    Display* dpy = open_display(config.display);
    if (!dpy)
        throw std::runtime_error("output.window.display \"" + config.display +
                                 "\": cannot open the X11 display (tried for 2 s)");
    display_ = dpy;
    try {
        rect_ = x11_output_rect(dpy, config.output_name);
    } catch (...) {
        XCloseDisplay(dpy);
        throw;
    }
    if (!config.fullscreen) rect_ = {rect_.x, rect_.y, raster_width, raster_height};
    const int screen = DefaultScreen(dpy);
    Visual* visual = DefaultVisual(dpy, screen);
    visual_id_ = static_cast<uint32_t>(XVisualIDFromVisual(visual));
    XSetWindowAttributes a{};
    a.background_pixel = BlackPixel(dpy, screen);
    a.override_redirect = config.fullscreen ? True : False;
    a.event_mask = StructureNotifyMask | ExposureMask;
    window_ = XCreateWindow(dpy, RootWindow(dpy, screen), rect_.x, rect_.y, static_cast<unsigned>(rect_.width),
                            static_cast<unsigned>(rect_.height), 0, DefaultDepth(dpy, screen), InputOutput, visual,
                            CWBackPixel | CWOverrideRedirect | CWEventMask, &a);
    XStoreName(dpy, window_, "Cupola");
    remove_decorations(dpy, window_);
    cursor_ = invisible_cursor(dpy, window_);
    XDefineCursor(dpy, window_, cursor_);
    XMapRaised(dpy, window_);
    wait_mapped(dpy, window_);
    spdlog::info("window sink: {}x{} at ({}, {}) on display {}{}", rect_.width, rect_.height, rect_.x, rect_.y,
                 config.display, config.output_name.empty() ? "" : ", output " + config.output_name);
}

X11Window::~X11Window() {
    auto* dpy = static_cast<Display*>(display_);
    if (window_) XDestroyWindow(dpy, window_);
    if (cursor_) XFreeCursor(dpy, cursor_);
    XCloseDisplay(dpy);
}

EncodedImage X11Window::read_pixels() const {
    auto* dpy = static_cast<Display*>(display_);
    XSync(dpy, False);
    XImage* img = XGetImage(dpy, window_, 0, 0, static_cast<unsigned>(rect_.width), static_cast<unsigned>(rect_.height),
                            AllPlanes, ZPixmap);
    if (!img) throw std::runtime_error("X11: XGetImage of the window failed");
    EncodedImage out;
    out.width = rect_.width;
    out.height = rect_.height;
    out.rgba.resize(static_cast<size_t>(out.width) * out.height * 4);
    const unsigned long masks[3] = {img->red_mask, img->green_mask, img->blue_mask};
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            const unsigned long p = XGetPixel(img, x, y);
            uint8_t* d = &out.rgba[(static_cast<size_t>(y) * out.width + x) * 4];
            for (int c = 0; c < 3; ++c) d[c] = static_cast<uint8_t>((p & masks[c]) >> mask_shift(masks[c]));
            d[3] = 255;
        }
    XDestroyImage(img);
    return out;
}

}  // namespace cupola

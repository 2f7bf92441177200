#pragma once
// Where a slave's GL context lives, chosen from its sinks: headless (EGL device or Mesa
// surfaceless) for files only; an X11 window for the window sink; a KMS output's GBM surface for
// the KMS sink. The native window is opened first, then the context on its platform.
#include <memory>

#include "config/cluster_config.hpp"
#include "gl/egl_context.hpp"
#include "output/kms_display.hpp"
#include "output/x11_window.hpp"

namespace cupola {

class OutputSurface {
public:
    // raster_*: the projector frame's size (a window that is not fullscreen gets it).
    OutputSurface(const SinkConfig& sinks, int egl_device, int raster_width, int raster_height);
    ~OutputSurface();

    EglContext& egl() { return *egl_; }
    const EglContext& egl() const { return *egl_; }
    X11Window* window() { return window_.get(); }  // null unless the window sink runs
    KmsDisplay* kms() { return kms_.get(); }       // null unless the KMS sink runs

private:
    std::unique_ptr<X11Window> window_;
    std::unique_ptr<KmsDisplay> kms_;
    std::unique_ptr<EglContext> egl_;  // destroyed before the window it draws into
};

}  // namespace cupola

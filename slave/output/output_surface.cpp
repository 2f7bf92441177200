#include "output/output_surface.hpp"

namespace cupola {

OutputSurface::OutputSurface(const SinkConfig& sinks, int egl_device, int raster_width, int raster_height) {
    if (sinks.has("window")) {
        window_ = std::make_unique<X11Window>(sinks.window, raster_width, raster_height);
        egl_ = std::make_unique<EglContext>(EglWindowTarget{EglPlatform::X11, window_->native_display(),
                                                            window_->native_window(), window_->visual_id()});
    } else if (sinks.has("kms")) {
        kms_ = std::make_unique<KmsDisplay>(sinks.kms);
        egl_ = std::make_unique<EglContext>(
            EglWindowTarget{EglPlatform::Gbm, kms_->native_display(), kms_->native_window(), kms_->format()});
    } else {
        egl_ = std::make_unique<EglContext>(egl_device);
    }
}

OutputSurface::~OutputSurface() { egl_.reset(); }

}  // namespace cupola

#pragma once
// The KMS sink: the projector frame blitted into the GBM surface's back buffer through EGL
// (EGL_PLATFORM_GBM_KHR); on present, eglSwapBuffers and a page flip (kms_display.hpp).
#include "gl/egl_context.hpp"
#include "output/kms_display.hpp"
#include "output/output_sink.hpp"

namespace cupola {

class KmsSink : public OutputSink {
public:
    // egl: current, with a window surface on display's GBM surface.
    KmsSink(EglContext& egl, KmsDisplay& display) : egl_(egl), display_(display) {}
    std::string name() const override { return "kms"; }
    bool live() const override { return true; }
    void take(const ProjectorFrame& frame) override;
    void present() override;

private:
    EglContext& egl_;
    KmsDisplay& display_;
};

}  // namespace cupola

#pragma once
// A display output driven through the kernel's mode setting, with no display server: the DRM
// device named in the config, one connector and mode, a GBM surface that EGL renders into, and
// page flips, following Mesa's kmscube (drm-legacy.c) and the kernel's KMS documentation
// (Documentation/gpu/drm-kms.rst): drmModeSetCrtc for the first frame, then drmModePageFlip
// with a page-flip event per frame; a scanned-out buffer goes back to GBM only once the next
// one is on screen. The CRTC's earlier state is restored on exit.
#include <cstdint>
#include <string>

#include "config/cluster_config.hpp"

struct gbm_device;
struct gbm_surface;
struct gbm_bo;

namespace cupola {

class KmsDisplay {
public:
    // Throws naming output.kms.device, .connector or .mode when that one is wrong.
    explicit KmsDisplay(const KmsOutputConfig& config);
    ~KmsDisplay();
    KmsDisplay(const KmsDisplay&) = delete;
    KmsDisplay& operator=(const KmsDisplay&) = delete;

    void* native_display() const { return gbm_; }     // gbm_device*
    void* native_window() const { return surface_; }  // gbm_surface*
    uint32_t format() const;                          // the GBM format EGL's config must match
    int width() const { return width_; }
    int height() const { return height_; }
    // After eglSwapBuffers: scans out the new front buffer and waits until it is on screen.
    void flip();

private:
    void pick_output(const KmsOutputConfig& config);
    void release();
    uint32_t framebuffer_for(gbm_bo* bo);

    int fd_ = -1;
    uint32_t connector_id_ = 0, crtc_id_ = 0;
    void* mode_ = nullptr;        // drmModeModeInfo
    void* saved_crtc_ = nullptr;  // drmModeCrtc before we set it
    gbm_device* gbm_ = nullptr;
    gbm_surface* surface_ = nullptr;
    gbm_bo* shown_ = nullptr;  // the buffer on screen
    int width_ = 0, height_ = 0;
    std::string device_;
};

}  // namespace cupola

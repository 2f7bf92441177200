#pragma once
// An OpenGL 4.5 core context through EGL, on one of three platforms:
//  - headless (no window): EGL device platform (EGL_EXT_platform_device, device index selectable
//    for nodes with several GPUs), then Mesa's surfaceless platform (EGL_MESA_platform_surfaceless);
//  - an X11 window (EGL_KHR_platform_x11): the window sink (slave/output/window_sink);
//  - a GBM surface on a DRM device (EGL_KHR_platform_gbm): the KMS sink (slave/output/kms_sink).
// With a window surface the context draws into its default framebuffer and swap_buffers() shows it.
#include <cstdint>
#include <string>

namespace cupola {

enum class EglPlatform { X11, Gbm };

// A native window to draw into, opened by its sink before the context is made.
struct EglWindowTarget {
    EglPlatform platform = EglPlatform::X11;
    void* native_display = nullptr;  // X11: Display*; GBM: gbm_device*
    void* native_window = nullptr;   // X11: a pointer to the Window (EGL_EXT_platform_x11); GBM: gbm_surface*
    uint32_t native_visual = 0;      // the config's EGL_NATIVE_VISUAL_ID: X11 visual id or GBM format
};

struct EglContextInfo {
    std::string platform;   // "device", "surfaceless", "x11" or "gbm"
    int device_index = -1;  // the EGL device used, -1 for surfaceless
    int device_count = 0;   // EGL devices enumerated
    std::string vendor, renderer, version;
};

class EglContext {
public:
    // device_index -1: the first device that gives a 4.5 core context, else surfaceless.
    // device_index >= 0: that device or an error naming it (no silent fallback).
    explicit EglContext(int device_index = -1);
    // A context on the target's platform, current with a window surface on its window; the
    // config is the one whose native visual is target.native_visual. Throws naming what failed.
    explicit EglContext(const EglWindowTarget& target);
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    const EglContextInfo& info() const { return info_; }
    bool has_window() const { return surface_ != nullptr; }
    // Window contexts only: frames per swap (1: vsync) and the swap itself; both throw on failure.
    void set_swap_interval(int interval);
    void swap_buffers();

private:
    void release();
    void* display_ = nullptr;
    void* context_ = nullptr;
    void* surface_ = nullptr;  // the window surface, or none (headless)
    EglContextInfo info_;
};

}  // namespace cupola

#pragma once
// A headless OpenGL 4.5 core context through EGL: no X11, Wayland or GLFW.
// Order of preference: EGL device platform (EGL_EXT_platform_device, device index selectable
// for nodes with several GPUs), then Mesa's surfaceless platform (EGL_MESA_platform_surfaceless).
#include <string>

namespace cupola {

struct EglContextInfo {
    std::string platform;   // "device" or "surfaceless"
    int device_index = -1;  // the EGL device used, -1 for surfaceless
    int device_count = 0;   // EGL devices enumerated
    std::string vendor, renderer, version;
};

class EglContext {
public:
    // device_index -1: the first device that gives a 4.5 core context, else surfaceless.
    // device_index >= 0: that device or an error naming it (no silent fallback).
    explicit EglContext(int device_index = -1);
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    const EglContextInfo& info() const { return info_; }

private:
    void* display_ = nullptr;
    void* context_ = nullptr;
    EglContextInfo info_;
};

}  // namespace cupola

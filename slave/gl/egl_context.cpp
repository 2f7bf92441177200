#include "gl/egl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <spdlog/spdlog.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace cupola {

namespace {

std::string egl_error_name(EGLint e) {
    switch (e) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE:
            return "EGL_BAD_SURFACE";
        default:
            return "EGL error 0x" + [&] {
                char b[16];
                std::snprintf(b, sizeof b, "%x", e);
                return std::string(b);
            }();
    }
}

bool has_extension(const char* list, const char* name) {
    if (!list) return false;
    const size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

struct EglProcs {
    PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
};

EglProcs load_procs() {
    EglProcs p;
    p.query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    p.get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    p.query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    return p;
}

const EGLint kCoreContextAttrs[] = {
    EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};

// Initialises `dpy` and creates a current 4.5 core context on it; on failure returns the reason
// (and leaves nothing initialised).
std::string try_context(EGLDisplay dpy, EGLContext& out_ctx) {
    if (dpy == EGL_NO_DISPLAY) return "no EGL display (" + egl_error_name(eglGetError()) + ")";
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) return "eglInitialize failed (" + egl_error_name(eglGetError()) + ")";
    auto fail = [&](const std::string& what) {
        const std::string msg = what + " (" + egl_error_name(eglGetError()) + ")";
        eglTerminate(dpy);
        return msg;
    };
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("eglBindAPI(EGL_OPENGL_API) failed");
    const char* exts = eglQueryString(dpy, EGL_EXTENSIONS);
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(exts, "EGL_KHR_no_config_context") && !has_extension(exts, "EGL_MESA_configless_context")) {
        // A config is needed only to create the context: ask for any OpenGL-capable one.
        const EGLint attrs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(dpy, attrs, &config, 1, &n) || n < 1) return fail("no OpenGL-capable EGL config");
    }
    if (!has_extension(exts, "EGL_KHR_surfaceless_context")) return fail("display lacks EGL_KHR_surfaceless_context");
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, kCoreContextAttrs);
    if (ctx == EGL_NO_CONTEXT) return fail("eglCreateContext(OpenGL 4.5 core) failed");
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        eglDestroyContext(dpy, ctx);
        return fail("eglMakeCurrent(EGL_NO_SURFACE) failed");
    }
    out_ctx = ctx;
    return {};
}

// The window-capable OpenGL config whose native visual is `visual` (an X11 visual id or a GBM
// format, as kmscube matches it), or none.
EGLConfig window_config(EGLDisplay dpy, uint32_t visual) {
    const EGLint attrs[] = {EGL_SURFACE_TYPE,
                            EGL_WINDOW_BIT,
                            EGL_RENDERABLE_TYPE,
                            EGL_OPENGL_BIT,
                            EGL_RED_SIZE,
                            8,
                            EGL_GREEN_SIZE,
                            8,
                            EGL_BLUE_SIZE,
                            8,
                            EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(dpy, attrs, nullptr, 0, &n) || n < 1) return nullptr;
    std::vector<EGLConfig> configs(static_cast<size_t>(n));
    eglChooseConfig(dpy, attrs, configs.data(), n, &n);
    for (EGLint i = 0; i < n; ++i) {
        EGLint id = 0;
        if (eglGetConfigAttrib(dpy, configs[static_cast<size_t>(i)], EGL_NATIVE_VISUAL_ID, &id) &&
            static_cast<uint32_t>(id) == visual)
            return configs[static_cast<size_t>(i)];
    }
    return nullptr;
}

std::string gl_string(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "";
}

}  // namespace

EglContext::EglContext(int device_index) {
    const EglProcs procs = load_procs();
    const char* client_exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!procs.get_platform_display)
        throw std::runtime_error("EGL: eglGetPlatformDisplayEXT is not available (EGL_EXT_platform_base missing)");

    std::vector<EGLDeviceEXT> devices;
    std::string device_note;
    if (procs.query_devices && has_extension(client_exts, "EGL_EXT_platform_device")) {
        EGLint n = 0;
        if (procs.query_devices(0, nullptr, &n) && n > 0) {
            devices.resize(static_cast<size_t>(n));
            if (!procs.query_devices(n, devices.data(), &n)) n = 0;
            devices.resize(static_cast<size_t>(n));
        }
    } else {
        device_note = " (EGL_EXT_device_enumeration / EGL_EXT_platform_device not supported)";
    }
    info_.device_count = static_cast<int>(devices.size());

    std::string reasons;
    auto try_device = [&](int i) -> bool {
        EGLDisplay dpy = procs.get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<size_t>(i)], nullptr);
        EGLContext ctx = EGL_NO_CONTEXT;
        const std::string why = try_context(dpy, ctx);
        if (!why.empty()) {
            reasons += "; device " + std::to_string(i) + ": " + why;
            return false;
        }
        display_ = dpy;
        context_ = ctx;
        info_.platform = "device";
        info_.device_index = i;
        return true;
    };

    if (device_index >= 0) {
        if (device_index >= info_.device_count)
            throw std::runtime_error("EGL device " + std::to_string(device_index) + " requested but only " +
                                     std::to_string(info_.device_count) + " device" +
                                     (info_.device_count == 1 ? "" : "s") + " found" + device_note);
        if (!try_device(device_index))
            throw std::runtime_error("EGL device " + std::to_string(device_index) +
                                     " gives no OpenGL 4.5 core context" + reasons);
    } else {
        bool ok = false;
        for (int i = 0; i < info_.device_count && !ok; ++i) ok = try_device(i);
        if (!ok) {
            if (!has_extension(client_exts, "EGL_MESA_platform_surfaceless"))
                throw std::runtime_error("EGL: no device gives an OpenGL 4.5 core context (" +
                                         std::to_string(info_.device_count) + " found" + reasons +
                                         ") and EGL_MESA_platform_surfaceless is not available");
            EGLDisplay dpy = procs.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            EGLContext ctx = EGL_NO_CONTEXT;
            const std::string why = try_context(dpy, ctx);
            if (!why.empty())
                throw std::runtime_error("EGL: no OpenGL 4.5 core context: " + std::to_string(info_.device_count) +
                                         " device(s) found" + reasons + "; surfaceless platform: " + why);
            display_ = dpy;
            context_ = ctx;
            info_.platform = "surfaceless";
            info_.device_index = -1;
        }
    }
    info_.vendor = gl_string(GL_VENDOR);
    info_.renderer = gl_string(GL_RENDERER);
    info_.version = gl_string(GL_VERSION);
    spdlog::info("EGL {} platform (device {} of {}): {} / {} / {}", info_.platform, info_.device_index,
                 info_.device_count, info_.vendor, info_.renderer, info_.version);
}

EglContext::EglContext(const EglWindowTarget& target) {
    const EglProcs procs = load_procs();
    const bool x11 = target.platform == EglPlatform::X11;
    info_.platform = x11 ? "x11" : "gbm";
    const char* client_exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!procs.get_platform_display ||
        !has_extension(client_exts, x11 ? "EGL_KHR_platform_x11" : "EGL_KHR_platform_gbm"))
        throw std::runtime_error("EGL: the " + info_.platform + " platform is not available (" +
                                 (x11 ? "EGL_KHR_platform_x11" : "EGL_KHR_platform_gbm") + " missing)");
    const auto create_surface = reinterpret_cast<PFNEGLCREATEPLATFORMWINDOWSURFACEEXTPROC>(
        eglGetProcAddress("eglCreatePlatformWindowSurfaceEXT"));
    EGLDisplay dpy =
        procs.get_platform_display(x11 ? EGL_PLATFORM_X11_KHR : EGL_PLATFORM_GBM_KHR, target.native_display, nullptr);
    EGLint major = 0, minor = 0;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor))
        throw std::runtime_error("EGL " + info_.platform + ": no display (" + egl_error_name(eglGetError()) + ")");
    display_ = dpy;  // from here on the destructor cleans up
    auto fail = [&](const std::string& what) {
        const std::string msg = "EGL " + info_.platform + ": " + what + " (" + egl_error_name(eglGetError()) + ")";
        release();
        throw std::runtime_error(msg);
    };
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
    EGLConfig config = window_config(dpy, target.native_visual);
    if (!config) fail("no OpenGL window config with native visual 0x" + fmt::format("{:x}", target.native_visual));
    context_ = eglCreateContext(dpy, config, EGL_NO_CONTEXT, kCoreContextAttrs);
    if (context_ == EGL_NO_CONTEXT) fail("eglCreateContext(OpenGL 4.5 core) failed");
    if (create_surface) surface_ = create_surface(dpy, config, target.native_window, nullptr);
    if (surface_ == EGL_NO_SURFACE) fail("eglCreatePlatformWindowSurfaceEXT failed");
    if (!eglMakeCurrent(dpy, surface_, surface_, context_)) fail("eglMakeCurrent(window surface) failed");
    info_.vendor = gl_string(GL_VENDOR);
    info_.renderer = gl_string(GL_RENDERER);
    info_.version = gl_string(GL_VERSION);
    spdlog::info("EGL {} platform, window surface: {} / {} / {}", info_.platform, info_.vendor, info_.renderer,
                 info_.version);
}

void EglContext::set_swap_interval(int interval) {
    if (!surface_) throw std::logic_error("EGL: swap interval on a context without a window");
    if (!eglSwapInterval(display_, interval))
        throw std::runtime_error("EGL " + info_.platform + ": eglSwapInterval(" + std::to_string(interval) +
                                 ") failed (" + egl_error_name(eglGetError()) + ")");
}

void EglContext::swap_buffers() {
    if (!surface_) throw std::logic_error("EGL: swap on a context without a window");
    if (!eglSwapBuffers(display_, surface_))
        throw std::runtime_error("EGL " + info_.platform + ": eglSwapBuffers failed (" + egl_error_name(eglGetError()) +
                                 ")");
}

EglContext::~EglContext() { release(); }

void EglContext::release() {
    if (display_) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (surface_) eglDestroySurface(display_, surface_);
        if (context_) eglDestroyContext(display_, context_);
        eglTerminate(display_);
        display_ = context_ = surface_ = nullptr;
    }
}

}  // namespace cupola

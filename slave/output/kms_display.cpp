#include "output/kms_display.hpp"

#include <fcntl.h>
#include <gbm.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace cupola {

namespace {

constexpr uint32_t kFormat = GBM_FORMAT_XRGB8888;

std::string errno_text() { return std::strerror(errno); }

// The kernel's name of a connector: type name and index, e.g. "HDMI-A-1".
std::string connector_name(const drmModeConnector* c) {
    const char* type = drmModeGetConnectorTypeName(c->connector_type);
    return std::string(type ? type : "Unknown") + "-" + std::to_string(c->connector_type_id);
}

double refresh_hz(const drmModeModeInfo& m) {
    if (m.htotal == 0 || m.vtotal == 0) return m.vrefresh;
    return m.clock * 1000.0 / (static_cast<double>(m.htotal) * m.vtotal);
}

std::string mode_text(const drmModeModeInfo& m) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%dx%d@%.2f", m.hdisplay, m.vdisplay, refresh_hz(m));
    return buf;
}

// The mode the config names (size, and refresh within 0.5 Hz when given; the highest refresh
// otherwise), or the connector's preferred mode when it names none.
const drmModeModeInfo* pick_mode(const drmModeConnector* c, const KmsOutputConfig& config) {
    const drmModeModeInfo* best = nullptr;
    for (int i = 0; i < c->count_modes; ++i) {
        const drmModeModeInfo& m = c->modes[i];
        if (config.mode_width == 0) {
            if (m.type & DRM_MODE_TYPE_PREFERRED) return &m;
            if (!best) best = &m;  // no preferred one: the first (the kernel lists the largest first)
            continue;
        }
        if (m.hdisplay != config.mode_width || m.vdisplay != config.mode_height) continue;
        if (config.mode_refresh_hz > 0.0 && std::abs(refresh_hz(m) - config.mode_refresh_hz) > 0.5) continue;
        if (!best || refresh_hz(m) > refresh_hz(*best)) best = &m;
    }
    return best;
}

// A CRTC that can drive the connector: its encoder's current one, else any its encoders allow.
uint32_t pick_crtc(int fd, const drmModeRes* res, const drmModeConnector* c) {
    if (drmModeEncoder* e = c->encoder_id ? drmModeGetEncoder(fd, c->encoder_id) : nullptr) {
        const uint32_t crtc = e->crtc_id;
        drmModeFreeEncoder(e);
        if (crtc) return crtc;
    }
    for (int i = 0; i < c->count_encoders; ++i) {
        drmModeEncoder* e = drmModeGetEncoder(fd, c->encoders[i]);
        if (!e) continue;
        const uint32_t possible = e->possible_crtcs;
        drmModeFreeEncoder(e);
        for (int k = 0; k < res->count_crtcs; ++k)
            if (possible & (1u << k)) return res->crtcs[k];
    }
    return 0;
}

void on_page_flip(int, unsigned, unsigned, unsigned, void* waiting) { *static_cast<bool*>(waiting) = false; }

void destroy_framebuffer(gbm_bo* bo, void* data) {
    const auto fb = static_cast<uint32_t>(reinterpret_cast<uintptr_t>(data));
    if (fb) drmModeRmFB(gbm_device_get_fd(gbm_bo_get_device(bo)), fb);
}

}  // namespace

KmsDisplay::KmsDisplay(const KmsOutputConfig& config) : device_(config.device) {
    fd_ = ::open(config.device.c_str(), O_RDWR | O_CLOEXEC);
    if (fd_ < 0)
        throw std::runtime_error("output.kms.device \"" + config.device + "\": cannot open (" + errno_text() + ")");
    try {
        pick_output(config);
        gbm_ = gbm_create_device(fd_);
        if (!gbm_) throw std::runtime_error("output.kms.device \"" + device_ + "\": no GBM device on it");
        surface_ = gbm_surface_create(gbm_, static_cast<uint32_t>(width_), static_cast<uint32_t>(height_), kFormat,
                                      GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
        if (!surface_) throw std::runtime_error("output.kms.device \"" + device_ + "\": gbm_surface_create failed");
    } catch (...) {
        release();
        throw;
    }
}

// The connector, mode and CRTC the config names (first connected connector, preferred mode
// when it names none).
void KmsDisplay::pick_output(const KmsOutputConfig& config) {
    std::unique_ptr<drmModeRes, void (*)(drmModeRes*)> res(drmModeGetResources(fd_), drmModeFreeResources);
    if (!res)
        throw std::runtime_error("output.kms.device \"" + device_ + "\": not a mode-setting device (" + errno_text() +
                                 ")");
    std::string seen;
    for (int i = 0; i < res->count_connectors && !connector_id_; ++i) {
        drmModeConnector* c = drmModeGetConnector(fd_, res->connectors[i]);
        if (!c) continue;
        const std::string name = connector_name(c);
        seen += (seen.empty() ? "" : ", ") + name + (c->connection == DRM_MODE_CONNECTED ? "" : " (disconnected)");
        const bool wanted = config.connector.empty() ? c->connection == DRM_MODE_CONNECTED && c->count_modes > 0
                                                     : name == config.connector;
        if (wanted) {
            std::string modes;
            for (int m = 0; m < c->count_modes; ++m) modes += (m ? ", " : "") + mode_text(c->modes[m]);
            const drmModeModeInfo* mode = pick_mode(c, config);
            const uint32_t crtc = mode ? pick_crtc(fd_, res.get(), c) : 0;
            const uint32_t id = c->connector_id;
            if (mode) mode_ = new drmModeModeInfo(*mode);
            drmModeFreeConnector(c);
            if (!mode)
                throw std::runtime_error("output.kms.mode: connector " + name +
                                         " has no such mode (modes: " + (modes.empty() ? "none" : modes) + ")");
            if (!crtc) throw std::runtime_error("output.kms.connector \"" + name + "\": no CRTC can drive it");
            connector_id_ = id;
            crtc_id_ = crtc;
            continue;
        }
        drmModeFreeConnector(c);
    }
    if (!connector_id_)
        throw std::runtime_error("output.kms.connector \"" + config.connector + "\": no such connected connector on " +
                                 device_ + " (connectors: " + (seen.empty() ? "none" : seen) + ")");
    const auto* m = static_cast<const drmModeModeInfo*>(mode_);
    width_ = m->hdisplay;
    height_ = m->vdisplay;
    saved_crtc_ = drmModeGetCrtc(fd_, crtc_id_);
    spdlog::info("kms sink: {} on {}, mode {}, CRTC {}",
                 config.connector.empty() ? "first connector" : config.connector, device_, mode_text(*m), crtc_id_);
}

uint32_t KmsDisplay::format() const { return kFormat; }

uint32_t KmsDisplay::framebuffer_for(gbm_bo* bo) {
    if (void* data = gbm_bo_get_user_data(bo)) return static_cast<uint32_t>(reinterpret_cast<uintptr_t>(data));
    const uint32_t handles[4] = {gbm_bo_get_handle(bo).u32, 0, 0, 0};
    const uint32_t pitches[4] = {gbm_bo_get_stride(bo), 0, 0, 0};
    const uint32_t offsets[4] = {0, 0, 0, 0};
    uint32_t fb = 0;
    if (drmModeAddFB2(fd_, gbm_bo_get_width(bo), gbm_bo_get_height(bo), kFormat, handles, pitches, offsets, &fb, 0))
        throw std::runtime_error("kms sink: drmModeAddFB2 failed on " + device_ + " (" + errno_text() + ")");
    gbm_bo_set_user_data(bo, reinterpret_cast<void*>(static_cast<uintptr_t>(fb)), destroy_framebuffer);
    return fb;
}

void KmsDisplay::flip() {
    gbm_bo* next = gbm_surface_lock_front_buffer(surface_);
    if (!next) throw std::runtime_error("kms sink: no front buffer after eglSwapBuffers");
    const uint32_t fb = framebuffer_for(next);
    if (!shown_) {
        if (drmModeSetCrtc(fd_, crtc_id_, fb, 0, 0, &connector_id_, 1, static_cast<drmModeModeInfo*>(mode_)))
            throw std::runtime_error("kms sink: drmModeSetCrtc failed on " + device_ + " (" + errno_text() + ")");
    } else {
        bool waiting = true;
        if (drmModePageFlip(fd_, crtc_id_, fb, DRM_MODE_PAGE_FLIP_EVENT, &waiting))
            throw std::runtime_error("kms sink: drmModePageFlip failed on " + device_ + " (" + errno_text() + ")");
        drmEventContext events{};
        events.version = 2;
        events.page_flip_handler = on_page_flip;
        while (waiting) {
            pollfd p{fd_, POLLIN, 0};
            const int n = ::poll(&p, 1, 1000);
            if (n == 0) throw std::runtime_error("kms sink: no page-flip event from " + device_ + " within 1 s");
            if (n < 0 && errno != EINTR)
                throw std::runtime_error("kms sink: poll on " + device_ + " failed (" + errno_text() + ")");
            if (p.revents & POLLIN) drmHandleEvent(fd_, &events);
        }
        gbm_surface_release_buffer(surface_, shown_);
    }
    shown_ = next;
}

KmsDisplay::~KmsDisplay() { release(); }

void KmsDisplay::release() {
    if (auto* saved = static_cast<drmModeCrtc*>(saved_crtc_)) {
        drmModeSetCrtc(fd_, saved->crtc_id, saved->buffer_id, saved->x, saved->y, &connector_id_, 1, &saved->mode);
        drmModeFreeCrtc(saved);
        saved_crtc_ = nullptr;
    }
    if (shown_ && surface_) gbm_surface_release_buffer(surface_, shown_);
    shown_ = nullptr;
    if (surface_) gbm_surface_destroy(surface_);
    surface_ = nullptr;
    if (gbm_) gbm_device_destroy(gbm_);
    gbm_ = nullptr;
    delete static_cast<drmModeModeInfo*>(mode_);
    mode_ = nullptr;
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

}  // namespace cupola

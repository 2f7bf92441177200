#pragma once
// Emulated USB HID devices for tests, on umockdev: a testbed with a root hub on bus 1 into which
// a test plugs navigation devices. libusb finds them through its real Linux code (sysfs, udev
// events) and talks to them through real ioctls on /dev/bus/usb/001/NNN, which umockdev's
// preload library hands to the usbdevfs emulation below (claim, kernel-driver detach/attach,
// interrupt URBs submitted, reaped, discarded, and ended with -ENODEV on unplug).
//
// The process must run with umockdev's preload library (umockdev-wrapper PROGRAM); ctest runs
// test_usb_input that way. Only one UsbTestbed may exist at a time (it owns the process's /sys).
//
//   cupola::test::UsbTestbed bed;
//   auto& mouse = bed.add_device(cupola::test::space_navigator());
//   mouse.send_report(cupola::test::spacemouse_report(1, 175, 0, 0));  // report 1: x = +175
//   ... UsbInput reads it; bed.unplug(mouse) pulls the cable.
//
// Timing: a report sent while the host waits in a reap is handed over at once (an idle source
// on umockdev's worker thread); a reap with nothing to hand over waits up to 1 ms before it
// answers EAGAIN (see kHoldMs), so with several devices open a report can wait that long for
// its device's turn in libusb's event loop.
//
// Header-only; needs umockdev-1.0 (pkg-config), not libusb.
#include <fcntl.h>
#include <linux/capability.h>
#include <linux/usbdevice_fs.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <umockdev.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace cupola::test {

// ---- what a device is ------------------------------------------------------------------------

struct EmulatedUsbDeviceSpec {
    std::string product = "emulated HID device";
    uint16_t vendor_id = 0;
    uint16_t product_id = 0;
    uint8_t port = 0;             // root-hub port (sysfs name 1-<port>); 0: the next free one
    uint8_t endpoint = 0x81;      // interrupt-IN endpoint address
    uint16_t max_packet = 8;      // its wMaxPacketSize
    uint8_t interface_class = 3;  // HID
    bool kernel_driver = true;    // usbhid is bound until the host detaches it
};

inline EmulatedUsbDeviceSpec space_navigator() { return {"SpaceNavigator", 0x046d, 0xc626, 0, 0x81, 7}; }
inline EmulatedUsbDeviceSpec spacemouse_compact() { return {"SpaceMouse Compact", 0x256f, 0xc635, 0, 0x81, 13}; }
inline EmulatedUsbDeviceSpec dual_action() { return {"Logitech Dual Action", 0x046d, 0xc216, 0, 0x81, 8}; }
inline EmulatedUsbDeviceSpec dualshock4() { return {"Wireless Controller", 0x054c, 0x05c4, 0, 0x84, 64}; }

// ---- reports ---------------------------------------------------------------------------------

inline void put_le16(std::vector<uint8_t>& v, int16_t x) {
    v.push_back(static_cast<uint8_t>(static_cast<uint16_t>(x) & 0xff));
    v.push_back(static_cast<uint8_t>(static_cast<uint16_t>(x) >> 8));
}
// 3Dconnexion report `id` with three int16 (report 1: x y z, report 2: rx ry rz): 7 bytes.
inline std::vector<uint8_t> spacemouse_report(uint8_t id, int16_t a, int16_t b, int16_t c) {
    std::vector<uint8_t> v{id};
    for (int16_t x : {a, b, c}) put_le16(v, x);
    return v;
}
// The newer form of report 1: all six axes, 13 bytes.
inline std::vector<uint8_t> spacemouse_report6(int16_t x, int16_t y, int16_t z, int16_t rx, int16_t ry, int16_t rz) {
    std::vector<uint8_t> v{1};
    for (int16_t a : {x, y, z, rx, ry, rz}) put_le16(v, a);
    return v;
}
// Report 3: the button bitmask (2 bytes).
inline std::vector<uint8_t> spacemouse_buttons(uint16_t mask) {
    return {3, static_cast<uint8_t>(mask & 0xff), static_cast<uint8_t>(mask >> 8)};
}
// Logitech Dual Action (DirectInput): 8 bytes, no id; hat centred (8); buttons 1..12 as bits 0..11.
inline std::vector<uint8_t> dual_action_report(uint8_t lx, uint8_t ly, uint8_t rx, uint8_t ry, uint16_t buttons = 0) {
    return {lx,
            ly,
            rx,
            ry,
            static_cast<uint8_t>(0x08 | ((buttons & 0xf) << 4)),
            static_cast<uint8_t>((buttons >> 4) & 0xff),
            0,
            0xff};
}
// DualShock 4 over USB: report 1, 64 bytes; hat centred (8).
inline std::vector<uint8_t> dualshock4_report(uint8_t lx, uint8_t ly, uint8_t rx, uint8_t ry, uint8_t l2 = 0,
                                              uint8_t r2 = 0, uint8_t face_buttons = 0, uint8_t shoulder_buttons = 0) {
    std::vector<uint8_t> v(64, 0);
    v[0] = 1;
    v[1] = lx, v[2] = ly, v[3] = rx, v[4] = ry;
    v[5] = static_cast<uint8_t>(0x08 | (face_buttons << 4));
    v[6] = shoulder_buttons;
    v[8] = l2, v[9] = r2;
    return v;
}

// Device descriptor + configuration (one HID interface, one interrupt-IN endpoint), as the
// sysfs "descriptors" attribute and a usbfs read() give them.
inline std::vector<uint8_t> usb_descriptors(const EmulatedUsbDeviceSpec& s) {
    auto lo = [](unsigned v) { return static_cast<uint8_t>(v & 0xff); };
    auto hi = [](unsigned v) { return static_cast<uint8_t>((v >> 8) & 0xff); };
    return {// device: USB 2.0, class per interface, ep0 64 bytes, bcdDevice 1.00, 1 configuration
            18, 1, 0x00, 0x02, 0, 0, 0, 64, lo(s.vendor_id), hi(s.vendor_id), lo(s.product_id), hi(s.product_id), 0x00,
            0x01, 0, 0, 0, 1,
            // configuration 1: 34 bytes in all, 1 interface, bus powered, 100 mA
            9, 2, 34, 0, 1, 1, 0, 0x80, 50,
            // interface 0: 1 endpoint, class HID (or spec.interface_class)
            9, 4, 0, 0, 1, s.interface_class, 0, 0, 0,
            // HID descriptor: HID 1.11, one report descriptor of 0 bytes (nobody reads it here)
            9, 0x21, 0x11, 0x01, 0, 1, 0x22, 0, 0,
            // endpoint: interrupt IN, 8 ms
            7, 5, s.endpoint, 3, lo(s.max_packet), hi(s.max_packet), 8};
}

// ---- one emulated device ---------------------------------------------------------------------

// The device side of one emulated device: what it will send, and what the host did to it.
// Thread-safe; the usbdevfs calls arrive on umockdev's worker thread.
class EmulatedUsbDevice {
public:
    const EmulatedUsbDeviceSpec& spec() const { return spec_; }
    int bus() const { return 1; }
    int address() const { return address_; }
    const std::string& sysname() const { return sysname_; }  // "1-4"
    const std::string& syspath() const { return syspath_; }  // "/sys/devices/.../usb1/1-4"
    std::string devnode() const {                            // "/dev/bus/usb/001/004"
        char b[32];
        std::snprintf(b, sizeof b, "/dev/bus/usb/001/%03d", address_);
        return b;
    }

    // Queues a report; the host gets it with the next interrupt-IN URB it reaps.
    void send_report(std::vector<uint8_t> report) {
        {
            std::lock_guard lock(s_->mutex);
            s_->reports.push_back(std::move(report));
        }
        kick();
    }
    // Another program holds the interface (claims fail with EBUSY) until set_busy(false).
    void set_busy(bool busy) {
        std::lock_guard lock(s_->mutex);
        s_->busy = busy;
    }
    size_t reports_pending() const {
        std::lock_guard lock(s_->mutex);
        return s_->reports.size();
    }
    size_t reports_delivered() const {
        std::lock_guard lock(s_->mutex);
        return s_->delivered;
    }
    int urbs_in_flight() const {
        std::lock_guard lock(s_->mutex);
        return static_cast<int>(s_->flying.size());
    }
    int claims() const {
        std::lock_guard lock(s_->mutex);
        return s_->claims;
    }
    int releases() const {
        std::lock_guard lock(s_->mutex);
        return s_->releases;
    }
    int driver_detaches() const {
        std::lock_guard lock(s_->mutex);
        return s_->detaches;
    }
    int driver_reattaches() const {
        std::lock_guard lock(s_->mutex);
        return s_->reattaches;
    }
    bool kernel_driver_bound() const {
        std::lock_guard lock(s_->mutex);
        return s_->driver_bound;
    }
    bool unplugged() const {
        std::lock_guard lock(s_->mutex);
        return s_->unplugged;
    }

    ~EmulatedUsbDevice() {
        if (handler_ != nullptr) {
            g_signal_handlers_disconnect_by_data(handler_, s_.get());
            g_object_unref(handler_);
        }
    }
    EmulatedUsbDevice(const EmulatedUsbDevice&) = delete;
    EmulatedUsbDevice& operator=(const EmulatedUsbDevice&) = delete;

private:
    friend class UsbTestbed;

    // A URB the host submitted: the usbdevfs_urb and its buffer, resolved into local copies that
    // umockdev writes back into the host process when the reap that returns it completes.
    struct Urb {
        UMockdevIoctlData* urb = nullptr;
        UMockdevIoctlData* buffer = nullptr;
    };
    struct State : std::enable_shared_from_this<State> {
        ~State() {
            for (auto* q : {&flying, &discarded})
                for (Urb& u : *q) {
                    g_object_unref(u.buffer);
                    g_object_unref(u.urb);
                }
            if (held != nullptr) g_object_unref(held);
            if (worker != nullptr) g_main_context_unref(worker);
        }
        EmulatedUsbDeviceSpec spec;
        std::mutex mutex;
        std::deque<std::vector<uint8_t>> reports;
        std::deque<Urb> flying, discarded;
        UMockdevIoctlClient* held = nullptr;  // a reap waiting (≤ kHoldMs) for a report
        GMainContext* worker = nullptr;       // umockdev's ioctl thread context
        bool worker_known = false;
        size_t delivered = 0;
        int claims = 0, releases = 0, detaches = 0, reattaches = 0;
        bool driver_bound = true, claimed = false, unplugged = false, busy = false;
        int address = 0;
        std::vector<uint8_t> descriptors;
    };
    // A reap with nothing to return waits this long before answering EAGAIN, like poll() on a
    // real usbfs node; a report, a discard or an unplug answers it at once. This keeps libusb's
    // event loop (which sees the emulated node as always ready) from spinning.
    static constexpr guint kHoldMs = 1;

    EmulatedUsbDevice(EmulatedUsbDeviceSpec spec, int address, std::string sysname, std::string syspath)
        : spec_(std::move(spec)),
          address_(address),
          sysname_(std::move(sysname)),
          syspath_(std::move(syspath)),
          s_(std::make_shared<State>()) {
        s_->spec = spec_;
        s_->driver_bound = spec_.kernel_driver;
        s_->address = address_;
        s_->descriptors = usb_descriptors(spec_);
        handler_ = umockdev_ioctl_base_new();
        g_signal_connect(handler_, "handle-ioctl", G_CALLBACK(&EmulatedUsbDevice::on_ioctl), s_.get());
        g_signal_connect(handler_, "handle-read", G_CALLBACK(&EmulatedUsbDevice::on_read), s_.get());
    }

    void mark_unplugged() {
        {
            std::lock_guard lock(s_->mutex);
            s_->unplugged = true;
        }
        kick();
    }

    // Answers a waiting reap now: with a report if one is queued (EAGAIN otherwise).
    void kick() { schedule(s_, 0); }

    // Runs answer_held(s, true) on umockdev's worker thread after delay_ms (0: as soon as it can),
    // so that every umockdev call stays on that thread.
    static void schedule(const std::shared_ptr<State>& s, guint delay_ms) {
        GMainContext* worker = nullptr;
        {
            std::lock_guard lock(s->mutex);
            worker = s->worker;
        }
        if (worker == nullptr) return;  // nothing was ever asked, so nothing waits
        GSource* src = delay_ms == 0 ? g_idle_source_new() : g_timeout_source_new(delay_ms);
        auto* keep = new std::shared_ptr<State>(s);
        g_source_set_callback(
            src,
            [](gpointer p) -> gboolean {
                answer_held(**static_cast<std::shared_ptr<State>*>(p), true);
                return G_SOURCE_REMOVE;
            },
            keep, [](gpointer p) { delete static_cast<std::shared_ptr<State>*>(p); });
        g_source_attach(src, worker);
        g_source_unref(src);
    }

    // Hands a URB back through the reap `client` asked for (caller holds the mutex).
    static void reap(UMockdevIoctlClient* client, std::deque<Urb>& from, int status, const std::vector<uint8_t>* data) {
        Urb u = from.front();
        from.pop_front();
        auto* urb = reinterpret_cast<usbdevfs_urb*>(u.urb->data);
        urb->status = status;
        urb->actual_length = 0;
        if (data != nullptr) {
            const size_t n = std::min<size_t>(data->size(), static_cast<size_t>(urb->buffer_length));
            std::memcpy(u.buffer->data, data->data(), n);
            urb->actual_length = static_cast<int>(n);
        }
        UMockdevIoctlData* ptr =
            umockdev_ioctl_data_resolve(umockdev_ioctl_client_get_arg(client), 0, sizeof(void*), nullptr);
        umockdev_ioctl_data_set_ptr(ptr, 0, u.urb);
        umockdev_ioctl_client_complete(client, 0, 0);
        g_object_unref(ptr);
        g_object_unref(u.buffer);
        g_object_unref(u.urb);
    }

    // Answers a reap if there is something to answer it with (or, when `timeout`, with EAGAIN).
    // Returns true when `client` was answered. Caller holds the mutex.
    static bool try_reap(State& s, UMockdevIoctlClient* client, bool timeout) {
        if (!s.discarded.empty()) {
            reap(client, s.discarded, -ENOENT, nullptr);
        } else if (s.unplugged && !s.flying.empty()) {
            reap(client, s.flying, -ENODEV, nullptr);
        } else if (s.unplugged) {
            umockdev_ioctl_client_complete(client, -1, ENODEV);
        } else if (!s.flying.empty() && !s.reports.empty()) {
            const std::vector<uint8_t> report = std::move(s.reports.front());
            s.reports.pop_front();
            reap(client, s.flying, 0, &report);
            ++s.delivered;
        } else if (timeout) {
            umockdev_ioctl_client_complete(client, -1, EAGAIN);
        } else {
            return false;
        }
        return true;
    }

    static void answer_held(State& s, bool timeout) {
        std::lock_guard lock(s.mutex);
        if (s.held == nullptr) return;
        if (try_reap(s, s.held, timeout)) {
            g_object_unref(s.held);
            s.held = nullptr;
        }
    }

    static gboolean on_read(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer p) {
        // A usbfs node reads as the device's descriptors (libusb_wrap_sys_device reads them).
        State& s = *static_cast<State*>(p);
        UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
        std::lock_guard lock(s.mutex);
        const size_t n = std::min<size_t>(s.descriptors.size(), static_cast<size_t>(arg->data_len));
        std::memcpy(arg->data, s.descriptors.data(), n);
        umockdev_ioctl_client_complete(client, static_cast<glong>(n), 0);
        return TRUE;
    }

    static gboolean on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer p) {
        State& s = *static_cast<State*>(p);
        const gulong request = umockdev_ioctl_client_get_request(client);
        UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
        auto done = [&](glong result, int err) {
            umockdev_ioctl_client_complete(client, result, err);
            return TRUE;
        };
        std::unique_lock lock(s.mutex);
        if (!s.worker_known) {  // umockdev's worker runs its own main context; without one, no waiting
            s.worker_known = true;
            GMainContext* c = g_main_context_get_thread_default();
            s.worker = c != nullptr ? g_main_context_ref(c) : nullptr;
        }
        const bool reaping = request == USBDEVFS_REAPURB || request == USBDEVFS_REAPURBNDELAY;
        if (s.unplugged && !reaping) return done(-1, ENODEV);

        switch (request) {
            case USBDEVFS_GET_CAPABILITIES: {
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(uint32_t), nullptr);
                *reinterpret_cast<uint32_t*>(d->data) = USBDEVFS_CAP_BULK_CONTINUATION |
                                                        USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
                                                        USBDEVFS_CAP_REAP_AFTER_DISCONNECT;
                g_object_unref(d);
                return done(0, 0);
            }
            case USBDEVFS_CONNECTINFO: {
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_connectinfo), nullptr);
                reinterpret_cast<usbdevfs_connectinfo*>(d->data)->devnum = static_cast<unsigned>(s.address);
                reinterpret_cast<usbdevfs_connectinfo*>(d->data)->slow = 0;
                g_object_unref(d);
                return done(0, 0);
            }
            case USBDEVFS_GETDRIVER: {
                if (!s.driver_bound) return done(-1, ENODATA);
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_getdriver), nullptr);
                std::strcpy(reinterpret_cast<usbdevfs_getdriver*>(d->data)->driver, "usbhid");
                g_object_unref(d);
                return done(0, 0);
            }
            case USBDEVFS_DISCONNECT_CLAIM:  // detach the kernel driver (unless it is usbfs) and claim
                if (s.busy) return done(-1, EBUSY);
                if (s.driver_bound) ++s.detaches;
                s.driver_bound = false;
                s.claimed = true;
                ++s.claims;
                return done(0, 0);
            case USBDEVFS_CLAIMINTERFACE:
                if (s.driver_bound || s.busy) return done(-1, EBUSY);
                s.claimed = true;
                ++s.claims;
                return done(0, 0);
            case USBDEVFS_RELEASEINTERFACE:
                if (!s.claimed) return done(-1, EINVAL);
                s.claimed = false;
                ++s.releases;
                return done(0, 0);
            case USBDEVFS_IOCTL: {  // driver detach (DISCONNECT) / reattach (CONNECT)
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_ioctl), nullptr);
                const int code = reinterpret_cast<usbdevfs_ioctl*>(d->data)->ioctl_code;
                g_object_unref(d);
                if (code == static_cast<int>(USBDEVFS_DISCONNECT)) {
                    if (!s.driver_bound) return done(-1, ENODATA);
                    s.driver_bound = false;
                    ++s.detaches;
                    return done(0, 0);
                }
                if (code == static_cast<int>(USBDEVFS_CONNECT)) {
                    if (s.claimed) return done(-1, EBUSY);
                    if (s.spec.kernel_driver && !s.driver_bound) {
                        s.driver_bound = true;
                        ++s.reattaches;
                    }
                    return done(0, 0);
                }
                return done(-1, ENOTTY);
            }
            case USBDEVFS_CONTROL: {  // only GET_CONFIGURATION (libusb_wrap_sys_device asks): configuration 1
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_ctrltransfer), nullptr);
                auto* ctrl = reinterpret_cast<usbdevfs_ctrltransfer*>(d->data);
                if (ctrl->bRequestType != 0x80 || ctrl->bRequest != 0x08 || ctrl->wLength < 1) {
                    g_object_unref(d);
                    return done(-1, EPIPE);  // a stall, as a device answers requests it does not know
                }
                UMockdevIoctlData* data =
                    umockdev_ioctl_data_resolve(d, G_STRUCT_OFFSET(usbdevfs_ctrltransfer, data), 1, nullptr);
                data->data[0] = 1;
                g_object_unref(data);
                g_object_unref(d);
                return done(1, 0);
            }
            case USBDEVFS_CLEAR_HALT:
            case USBDEVFS_RESETEP:
            case USBDEVFS_SETINTERFACE:
            case USBDEVFS_SETCONFIGURATION:
                return done(0, 0);
            case USBDEVFS_SUBMITURB: {
                UMockdevIoctlData* urb_data = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
                auto* urb = reinterpret_cast<usbdevfs_urb*>(urb_data->data);
                if (urb->type != USBDEVFS_URB_TYPE_INTERRUPT || urb->endpoint != s.spec.endpoint || !s.claimed) {
                    g_object_unref(urb_data);
                    return done(-1, EINVAL);  // only the interrupt-IN endpoint of a claimed interface exists here
                }
                UMockdevIoctlData* buf = umockdev_ioctl_data_resolve(urb_data, G_STRUCT_OFFSET(usbdevfs_urb, buffer),
                                                                     static_cast<gsize>(urb->buffer_length), nullptr);
                s.flying.push_back({urb_data, buf});
                done(0, 0);
                if (s.held != nullptr && try_reap(s, s.held, false)) {
                    g_object_unref(s.held);
                    s.held = nullptr;
                }
                return TRUE;
            }
            case USBDEVFS_DISCARDURB: {
                const auto addr = reinterpret_cast<gulong>(*reinterpret_cast<void**>(arg->data));
                for (auto it = s.flying.begin(); it != s.flying.end(); ++it) {
                    if (it->urb->client_addr == addr) {
                        s.discarded.push_back(*it);
                        s.flying.erase(it);
                        done(0, 0);
                        lock.unlock();
                        answer_held(s, false);
                        return TRUE;
                    }
                }
                return done(-1, EINVAL);
            }
            case USBDEVFS_REAPURB:
            case USBDEVFS_REAPURBNDELAY: {
                if (try_reap(s, client, false)) return TRUE;
                if (s.held != nullptr) return done(-1, EAGAIN);    // one waiter at a time
                if (s.worker == nullptr) return done(-1, EAGAIN);  // no context to time the wait with
                s.held = static_cast<UMockdevIoctlClient*>(g_object_ref(client));
                lock.unlock();
                // The wait ends after kHoldMs with EAGAIN unless something answers it first.
                schedule(s.shared_from_this(), kHoldMs);
                return TRUE;
            }
            default:
                return done(-1, ENOTTY);
        }
    }

    EmulatedUsbDeviceSpec spec_;
    int address_;
    std::string sysname_, syspath_;
    std::shared_ptr<State> s_;
    UMockdevIoctlBase* handler_ = nullptr;
    bool announced_ = true;
};

// ---- the testbed ------------------------------------------------------------------------------

// How a device appears: with an "add" uevent (libusb's hotplug sees it), or only in /sys and
// /dev, as on a host where no udev daemon forwards events (a container): then only a rescan of
// /sys can find it.
enum class Announce { Uevent, Silently };

class UsbTestbed {
public:
    // true when the process runs with umockdev's preload library (umockdev-wrapper).
    static bool preloaded() {
        const char* p = std::getenv("LD_PRELOAD");
        return p != nullptr && std::strstr(p, "libumockdev-preload") != nullptr;
    }

    UsbTestbed() {
        if (!preloaded())
            throw std::runtime_error(
                "the USB tests need umockdev's preload library: run them as "
                "`umockdev-wrapper test_usb_input` (ctest does)");
        testbed_ = umockdev_testbed_new();
        gchar* root = umockdev_testbed_get_root_dir(testbed_);
        gchar* sys = umockdev_testbed_get_sys_dir(testbed_);
        root_ = root;
        sys_ = sys;
        g_free(root);
        g_free(sys);
        // The root hub of bus 1 (libusb derives port numbers from the parent chain).
        add_from_string(
            "P: " + std::string(kHubPath) +
            "\nN: bus/usb/001/001\nE: SUBSYSTEM=usb\nE: DEVTYPE=usb_device\nE: DRIVER=usb\n"
            "E: BUSNUM=001\nE: DEVNUM=001\nE: DEVNAME=/dev/bus/usb/001/001\n"
            "A: busnum=1\\n\nA: devnum=1\\n\nA: speed=480\\n\nA: bConfigurationValue=1\\n\n"
            "A: idVendor=1d6b\\n\nA: idProduct=0002\\n\n"
            "H: descriptors=12010002090001406b1d020006050302010109021900010100e0000904000001090000000705810304000c\n");
    }
    ~UsbTestbed() {
        g_object_unref(testbed_);  // stops umockdev's worker and removes the directory
        devices_.clear();
    }
    UsbTestbed(const UsbTestbed&) = delete;
    UsbTestbed& operator=(const UsbTestbed&) = delete;

    // Plugs a device into the next free port (or spec.port) with the next free address.
    EmulatedUsbDevice& add_device(const EmulatedUsbDeviceSpec& spec, Announce announce = Announce::Uevent) {
        const int port = spec.port != 0 ? spec.port : next_port_++;
        const int address = next_address_++;
        const std::string sysname = "1-" + std::to_string(port);
        const std::string devpath = std::string(kHubPath) + "/" + sysname;
        std::unique_ptr<EmulatedUsbDevice> dev(new EmulatedUsbDevice(spec, address, sysname, "/sys" + devpath));
        dev->announced_ = announce == Announce::Uevent;
        GError* error = nullptr;
        if (!umockdev_testbed_attach_ioctl(testbed_, dev->devnode().c_str(), dev->handler_, &error))
            throw std::runtime_error(take_message(error, "umockdev_testbed_attach_ioctl " + dev->devnode()));

        const std::string vid = format("%04x", spec.vendor_id), pid = format("%04x", spec.product_id);
        const std::string dev3 = format("%03d", address), devn = std::to_string(address);
        const std::vector<uint8_t> desc = usb_descriptors(spec);
        if (announce == Announce::Uevent) {
            add_from_string(
                "P: " + devpath + "\nN: bus/usb/001/" + dev3 +
                "\nE: SUBSYSTEM=usb\nE: DEVTYPE=usb_device\nE: DRIVER=usb\nE: BUSNUM=001\nE: DEVNUM=" + dev3 +
                "\nE: DEVNAME=/dev/bus/usb/001/" + dev3 + "\nA: busnum=1\\n\nA: devnum=" + devn +
                "\\n\nA: speed=12\\n\nA: bConfigurationValue=1\\n\nA: idVendor=" + vid + "\\n\nA: idProduct=" + pid +
                "\\n\nA: product=" + spec.product + "\\n\nH: descriptors=" + hex(desc) + "\n");
        } else {
            // What add_device writes, minus the uevent.
            namespace fs = std::filesystem;
            const fs::path dir = fs::path(sys_) / devpath.substr(1);
            fs::create_directories(dir);
            write(dir / "busnum", "1\n");
            write(dir / "devnum", devn + "\n");
            write(dir / "speed", "12\n");
            write(dir / "bConfigurationValue", "1\n");
            write(dir / "idVendor", vid + "\n");
            write(dir / "idProduct", pid + "\n");
            write(dir / "product", spec.product + "\n");
            write(dir / "descriptors", std::string(desc.begin(), desc.end()));
            write(dir / "uevent", "DEVTYPE=usb_device\nDRIVER=usb\nBUSNUM=001\nDEVNUM=" + dev3 +
                                      "\nDEVNAME=bus/usb/001/" + dev3 + "\n");
            fs::create_directory_symlink("../../../../../bus/usb", dir / "subsystem");
            fs::create_directories(fs::path(sys_) / "bus/usb/devices");
            fs::create_directory_symlink("../../.." + devpath, fs::path(sys_) / "bus/usb/devices" / sysname);
            const fs::path node = fs::path(root_) / dev->devnode().substr(1);
            fs::create_directories(node.parent_path());
            write(node, "");
        }
        devices_.push_back(std::move(dev));
        return *devices_.back();
    }

    // Pulls the cable: the device's URBs end with -ENODEV, every further call fails with
    // ENODEV, then the "remove" uevent and the sysfs entry and device node go away.
    void unplug(EmulatedUsbDevice& dev) {
        dev.mark_unplugged();
        if (dev.announced_) {
            umockdev_testbed_uevent(testbed_, dev.syspath().c_str(), "remove");
            umockdev_testbed_remove_device(testbed_, dev.syspath().c_str());
        } else {
            namespace fs = std::filesystem;
            fs::remove(fs::path(sys_) / "bus/usb/devices" / dev.sysname());
            fs::remove_all(fs::path(sys_) / dev.syspath().substr(5));
            fs::remove(fs::path(root_) / dev.devnode().substr(1));
        }
    }

    // chmod on the device node as the host sees it (/dev/bus/usb/001/NNN).
    void set_node_mode(const EmulatedUsbDevice& dev, mode_t mode) {
        const std::string node = root_ + dev.devnode();
        if (::chmod(node.c_str(), mode) != 0) throw std::runtime_error("chmod " + node + ": " + std::strerror(errno));
    }

    const std::string& root_dir() const { return root_; }

private:
    static constexpr const char* kHubPath = "/devices/pci0000:00/0000:00:14.0/usb1";

    static std::string format(const char* fmt, int value) {
        char b[16];
        std::snprintf(b, sizeof b, fmt, value);
        return b;
    }
    static std::string hex(const std::vector<uint8_t>& bytes) {
        static const char* digits = "0123456789abcdef";
        std::string s;
        for (uint8_t b : bytes) s += {digits[b >> 4], digits[b & 0xf]};
        return s;
    }
    static void write(const std::filesystem::path& p, const std::string& text) {
        std::ofstream out(p, std::ios::binary);
        out << text;
        if (!out) throw std::runtime_error("cannot write " + p.string());
    }
    static std::string take_message(GError* error, const std::string& what) {
        std::string m = what + ": " + (error != nullptr ? error->message : "failed");
        if (error != nullptr) g_error_free(error);
        return m;
    }
    void add_from_string(const std::string& description) {
        GError* error = nullptr;
        if (!umockdev_testbed_add_from_string(testbed_, description.c_str(), &error))
            throw std::runtime_error(take_message(error, "umockdev_testbed_add_from_string"));
    }

    UMockdevTestbed* testbed_ = nullptr;
    std::string root_, sys_;
    int next_port_ = 1;
    int next_address_ = 2;
    std::vector<std::unique_ptr<EmulatedUsbDevice>> devices_;
};

// ---- small helpers for tests that use the testbed ------------------------------------------------

// Polls `done` every millisecond until it is true or `timeout` passed; returns its last value.
template <class F>
bool wait_until(F done, std::chrono::milliseconds timeout = std::chrono::milliseconds(3000)) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (!done()) {
        if (std::chrono::steady_clock::now() >= end) return done();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return true;
}

// While it lives, file permissions apply to this thread even as root: CAP_DAC_OVERRIDE and
// CAP_DAC_READ_SEARCH leave its effective capability set (threads it starts meanwhile keep the
// reduced set for good). A device node with mode 000 then refuses open() with EACCES, as it
// does for an ordinary user. Without those capabilities in the first place it changes nothing.
class WithoutFileAccessOverride {
public:
    WithoutFileAccessOverride() {
        if (syscall(SYS_capget, &header_, saved_) != 0) return;
        __user_cap_data_struct reduced[2] = {saved_[0], saved_[1]};
        reduced[0].effective &= ~((1u << CAP_DAC_OVERRIDE) | (1u << CAP_DAC_READ_SEARCH));
        active_ = syscall(SYS_capset, &header_, reduced) == 0;
    }
    ~WithoutFileAccessOverride() {
        if (active_) syscall(SYS_capset, &header_, saved_);
    }
    WithoutFileAccessOverride(const WithoutFileAccessOverride&) = delete;
    WithoutFileAccessOverride& operator=(const WithoutFileAccessOverride&) = delete;

private:
    __user_cap_header_struct header_{_LINUX_CAPABILITY_VERSION_3, 0};
    __user_cap_data_struct saved_[2]{};
    bool active_ = false;
};

}  // namespace cupola::test

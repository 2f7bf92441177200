#include "input/usb_input.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <libusb.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <utility>

#include "util/monotonic_clock.hpp"

namespace cupola {

namespace {

// A device's place on the bus while it stays plugged in (a replug gets a new address).
struct BusAddress {
    int bus = 0;
    int address = 0;
    auto operator<=>(const BusAddress&) const = default;
};

std::string devnode_path(int bus, int address) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "/dev/bus/usb/%03d/%03d", bus, address);
    return buf;
}

// What a device node looked like when opening the device failed; a different stamp (udev changed
// its mode or group, or the device was replugged) is the signal to try again.
struct NodeStamp {
    bool exists = false;
    ino_t ino = 0;
    mode_t mode = 0;
    uid_t uid = 0;
    gid_t gid = 0;
    int64_t ctime_ns = 0;
    bool operator==(const NodeStamp&) const = default;
};

NodeStamp stamp_of(const std::string& path) {
    struct stat st {};
    NodeStamp s;
    if (::stat(path.c_str(), &st) != 0) return s;
    s.exists = true;
    s.ino = st.st_ino;
    s.mode = st.st_mode;
    s.uid = st.st_uid;
    s.gid = st.st_gid;
    s.ctime_ns = int64_t{st.st_ctim.tv_sec} * 1000000000 + st.st_ctim.tv_nsec;
    return s;
}

// The first line of a sysfs attribute ("" when it cannot be read).
std::string read_attribute(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    while (!line.empty() && (line.back() == '\n' || line.back() == ' ')) line.pop_back();
    return line;
}

std::optional<long> parse_number(const std::string& s, int base) {
    if (s.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, base);
    if (errno != 0 || end == s.c_str() || *end != '\0') return std::nullopt;
    return v;
}

// "usb 1-4.2 046d:c626": the bus-port path stays the same when the device is replugged into the
// same port (its address does not).
std::string key_for(const std::string& port_path, const DeviceModel& m) {
    return "usb " + port_path + " " + usb_id_string(m.vendor_id, m.product_id);
}

std::string port_path_of(libusb_device* dev) {
    uint8_t ports[8];
    const int n = libusb_get_port_numbers(dev, ports, sizeof ports);
    std::string s = std::to_string(libusb_get_bus_number(dev));
    if (n <= 0) return s + " addr " + std::to_string(libusb_get_device_address(dev));
    for (int i = 0; i < n; ++i) s += (i == 0 ? "-" : ".") + std::to_string(ports[i]);
    return s;
}

}  // namespace

nlohmann::json UsbInputCounters::to_json() const {
    return {{"devices_opened", devices_opened}, {"devices_closed", devices_closed},   {"reports", reports},
            {"bad_reports", bad_reports},       {"transfer_errors", transfer_errors}, {"access_denied", access_denied},
            {"open_failures", open_failures}};
}

std::string usb_access_denied_message(const DeviceModel& model, int bus, int address) {
    return "usb input: no permission to open " + model.name + " (" + usb_id_string(model.vendor_id, model.product_id) +
           ") on bus " + std::to_string(bus) + " address " + std::to_string(address) + " (" +
           devnode_path(bus, address) +
           "): the master needs read-write access to the device node. Install the udev rule shipped with Cupola: "
           "sudo cp configs/udev/70-cupola-navigation.rules /etc/udev/rules.d/ && sudo udevadm control --reload && "
           "sudo udevadm trigger (then the logged-in user and the plugdev group may open it; the master tries "
           "again by itself once the device node changes)";
}

// ---------------------------------------------------------------------------------------------
// Everything below runs on the event thread, except start(), stop() and the two readers, which
// touch only the mutex-protected counters and keys.
struct UsbInput::Impl {
    // One device we opened.
    struct Device {
        Impl* owner = nullptr;
        const DeviceModel* model = nullptr;  // into Impl::table, which never changes
        std::string key;
        BusAddress where;
        libusb_device_handle* handle = nullptr;
        int own_fd = -1;  // the device node we opened ourselves (sysfs rescan): closed after libusb_close
        int interface_number = -1;
        bool claimed = false;
        libusb_transfer* transfer = nullptr;
        std::vector<uint8_t> buffer;
        bool in_flight = false;
        bool closing = false;
        std::string close_reason;
        uint64_t close_deadline_ns = 0;
        int consecutive_errors = 0;
        bool bad_report_logged = false;
        NavSample sample;
    };

    Impl(std::vector<DeviceModel> t, InputHub& h, UsbInputOptions o) : table(std::move(t)), hub(h), opts(o) {}

    const std::vector<DeviceModel> table;
    InputHub& hub;
    const UsbInputOptions opts;

    libusb_context* ctx = nullptr;
    std::thread thread;
    std::atomic<bool> stopping{false};

    // Event thread only.
    std::vector<std::unique_ptr<Device>> devices;
    // Devices that could not be opened. Denied access is tried again only when the device node
    // changes; other failures (busy, odd descriptors) at every rescan. Either is logged once.
    struct Refusal {
        bool access = false;  // denied access (or a device that failed while read): retried when its node changes
        NodeStamp node;
    };
    std::map<BusAddress, Refusal> refused;
    std::vector<libusb_device*> arrived;  // hotplug arrivals (referenced), opened after the events
    std::vector<BusAddress> departed;     // hotplug departures
    std::set<BusAddress> sysfs_seen;      // table devices in /sys at the previous rescan
    bool hotplug_registered = false;
    libusb_hotplug_callback_handle hotplug_handle{};
    bool event_error_logged = false;

    // Shared.
    mutable std::mutex mutex;
    UsbInputCounters totals;
    std::vector<std::string> keys;

    void bump(uint64_t UsbInputCounters::*field) {
        std::lock_guard lock(mutex);
        ++(totals.*field);
    }

    void run();
    void rescan();
    void scan_sysfs(const std::set<BusAddress>& listed, std::set<BusAddress>& in_sysfs);
    bool should_try(BusAddress where);
    void refuse(BusAddress where, const DeviceModel& m, bool access, const std::string& why);
    void open_listed(libusb_device* dev);
    void attach(std::unique_ptr<Device> d, libusb_device_handle* handle, int own_fd);
    void begin_close(Device& d, const std::string& reason);
    void finish_closing(bool force);
    void handle_hotplug_queue();
    void on_report(Device& d, const libusb_transfer& t);
    void resubmit(Device& d);

    static void LIBUSB_CALL on_transfer(libusb_transfer* t);
    static int LIBUSB_CALL on_hotplug(libusb_context*, libusb_device* dev, libusb_hotplug_event event, void* self);
};

// ---- opening ----------------------------------------------------------------------------------

bool UsbInput::Impl::should_try(BusAddress where) {
    for (const auto& d : devices)
        if (d->where == where) return false;  // open, or still closing
    auto it = refused.find(where);
    return it == refused.end() || !it->second.access ||
           !(stamp_of(devnode_path(where.bus, where.address)) == it->second.node);
}

// Remembers a failed open; logs and counts it only the first time for this device.
void UsbInput::Impl::refuse(BusAddress where, const DeviceModel& m, bool access, const std::string& why) {
    const bool first = refused.find(where) == refused.end();
    refused[where] = Refusal{access, stamp_of(devnode_path(where.bus, where.address))};
    if (!first) return;
    if (access) {
        bump(&UsbInputCounters::access_denied);
        spdlog::error("{}", usb_access_denied_message(m, where.bus, where.address));
    } else {
        bump(&UsbInputCounters::open_failures);
        spdlog::warn("usb input: cannot use {} ({}) on bus {} address {}: {}", m.name,
                     usb_id_string(m.vendor_id, m.product_id), where.bus, where.address, why);
    }
}

void UsbInput::Impl::open_listed(libusb_device* dev) {
    libusb_device_descriptor desc{};
    if (libusb_get_device_descriptor(dev, &desc) != 0) return;
    const DeviceModel* m = find_device_model(table, desc.idVendor, desc.idProduct);
    if (m == nullptr) return;
    const BusAddress where{libusb_get_bus_number(dev), libusb_get_device_address(dev)};
    if (!should_try(where)) return;
    libusb_device_handle* handle = nullptr;
    const int rc = libusb_open(dev, &handle);
    if (rc != 0) {
        refuse(where, *m, rc == LIBUSB_ERROR_ACCESS, std::string("libusb_open: ") + libusb_error_name(rc));
        return;
    }
    auto d = std::make_unique<Device>();
    d->model = m;
    d->where = where;
    d->key = key_for(port_path_of(dev), *m);
    attach(std::move(d), handle, -1);
}

// Table devices in /sys that libusb does not list (it was never told about them): open their
// device node ourselves and hand it to libusb.
void UsbInput::Impl::scan_sysfs(const std::set<BusAddress>& listed, std::set<BusAddress>& in_sysfs) {
    const std::string base = "/sys/bus/usb/devices/";
    DIR* dir = ::opendir(base.c_str());
    if (dir == nullptr) return;
    std::vector<std::string> names;
    while (const dirent* e = ::readdir(dir)) {
        const std::string name = e->d_name;
        // Devices are "1-4", "1-4.2", "usb1"; interfaces have a colon ("1-4:1.0").
        if (name.empty() || name[0] == '.' || name.find(':') != std::string::npos) continue;
        names.push_back(name);
    }
    ::closedir(dir);

    for (const auto& name : names) {
        const std::string dev = base + name + "/";
        const auto vid = parse_number(read_attribute(dev + "idVendor"), 16);
        const auto pid = parse_number(read_attribute(dev + "idProduct"), 16);
        const auto bus = parse_number(read_attribute(dev + "busnum"), 10);
        const auto addr = parse_number(read_attribute(dev + "devnum"), 10);
        if (!vid || !pid || !bus || !addr) continue;
        const DeviceModel* m = find_device_model(table, static_cast<uint16_t>(*vid), static_cast<uint16_t>(*pid));
        if (m == nullptr) continue;
        const BusAddress where{static_cast<int>(*bus), static_cast<int>(*addr)};
        in_sysfs.insert(where);
        // Only a device that was already there at the previous rescan: a new one is udev's to
        // set up (node permissions) and to announce to libusb first.
        if (listed.count(where) || !sysfs_seen.count(where) || !should_try(where)) continue;

        const std::string node = devnode_path(where.bus, where.address);
        const int fd = ::open(node.c_str(), O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            const int err = errno;
            if (err == ENOENT) continue;  // udev has not made the node yet: next rescan
            refuse(where, *m, err == EACCES || err == EPERM, "open " + node + ": " + std::strerror(err));
            continue;
        }
        libusb_device_handle* handle = nullptr;
        const int rc = libusb_wrap_sys_device(ctx, static_cast<intptr_t>(fd), &handle);
        if (rc != 0) {
            ::close(fd);
            refuse(where, *m, rc == LIBUSB_ERROR_ACCESS,
                   std::string("libusb_wrap_sys_device: ") + libusb_error_name(rc));
            continue;
        }
        spdlog::info("usb input: {} at {} found by the rescan (libusb had no hotplug event for it)", m->name, node);
        auto d = std::make_unique<Device>();
        d->model = m;
        d->where = where;
        d->key = key_for(name, *m);
        attach(std::move(d), handle, fd);
    }
}

// Claims the HID interface, starts the interrupt-IN transfer and publishes the device.
void UsbInput::Impl::attach(std::unique_ptr<Device> d, libusb_device_handle* handle, int own_fd) {
    d->owner = this;
    d->handle = handle;
    d->own_fd = own_fd;
    const DeviceModel& m = *d->model;
    auto give_up = [&](const std::string& why) {
        if (d->claimed) libusb_release_interface(handle, d->interface_number);
        if (d->transfer) libusb_free_transfer(d->transfer);
        libusb_close(handle);
        if (own_fd >= 0) ::close(own_fd);
        refuse(d->where, m, false, why);
    };

    // The interface and its interrupt-IN endpoint.
    libusb_config_descriptor* cfg = nullptr;
    if (const int rc = libusb_get_active_config_descriptor(libusb_get_device(handle), &cfg); rc != 0) {
        give_up(std::string("no configuration descriptor: ") + libusb_error_name(rc));
        return;
    }
    uint8_t endpoint = 0;
    int packet = 0;
    for (int i = 0; i < cfg->bNumInterfaces && endpoint == 0; ++i) {
        if (cfg->interface[i].num_altsetting < 1) continue;
        const libusb_interface_descriptor& alt = cfg->interface[i].altsetting[0];
        const bool wanted = m.interface_number >= 0 ? alt.bInterfaceNumber == m.interface_number
                                                    : alt.bInterfaceClass == LIBUSB_CLASS_HID;
        if (!wanted) continue;
        for (int e = 0; e < alt.bNumEndpoints; ++e) {
            const libusb_endpoint_descriptor& ep = alt.endpoint[e];
            if ((ep.bmAttributes & 0x3) == LIBUSB_TRANSFER_TYPE_INTERRUPT &&
                (ep.bEndpointAddress & LIBUSB_ENDPOINT_IN)) {
                endpoint = ep.bEndpointAddress;
                packet = ep.wMaxPacketSize & 0x7ff;
                d->interface_number = alt.bInterfaceNumber;
                break;
            }
        }
    }
    libusb_free_config_descriptor(cfg);
    if (endpoint == 0) {
        give_up("no HID interface with an interrupt-IN endpoint");
        return;
    }

    // The kernel's HID driver lets go while we hold the interface and gets it back on release.
    libusb_set_auto_detach_kernel_driver(handle, 1);
    if (const int rc = libusb_claim_interface(handle, d->interface_number); rc != 0) {
        give_up("cannot claim interface " + std::to_string(d->interface_number) + ": " + libusb_error_name(rc) +
                (rc == LIBUSB_ERROR_BUSY ? " (another program holds it)" : ""));
        return;
    }
    d->claimed = true;

    d->buffer.assign(static_cast<size_t>(std::max(packet, 64)), 0);
    d->transfer = libusb_alloc_transfer(0);
    if (d->transfer == nullptr) {
        give_up("cannot allocate a transfer");
        return;
    }
    libusb_fill_interrupt_transfer(d->transfer, handle, endpoint, d->buffer.data(), packet > 0 ? packet : 64,
                                   &Impl::on_transfer, d.get(), 0);
    if (const int rc = libusb_submit_transfer(d->transfer); rc != 0) {
        give_up(std::string("cannot start reading: ") + libusb_error_name(rc));
        return;
    }
    d->in_flight = true;

    d->sample.connected = true;
    d->sample.device = m.name;
    hub.publish(d->key, d->sample);
    {
        std::lock_guard lock(mutex);
        ++totals.devices_opened;
        keys.push_back(d->key);
    }
    refused.erase(d->where);
    spdlog::info("usb input: reading {} ({}) as \"{}\": interface {}, endpoint 0x{:02x}", m.name,
                 usb_id_string(m.vendor_id, m.product_id), d->key, d->interface_number, endpoint);
    devices.push_back(std::move(d));
}

// ---- reading ----------------------------------------------------------------------------------

void UsbInput::Impl::on_report(Device& d, const libusb_transfer& t) {
    bump(&UsbInputCounters::reports);
    const ReportVerdict v = apply_report(d.model->layout, t.buffer, static_cast<size_t>(t.actual_length), d.sample);
    if (v == ReportVerdict::Applied) {
        d.sample.report_ns = monotonic_ns();
        ++d.sample.reports;
        hub.publish(d.key, d.sample);
    } else if (v != ReportVerdict::Ignored) {
        bump(&UsbInputCounters::bad_reports);
        if (!d.bad_report_logged) {  // once per device: a layout that does not fit shows in the log
            d.bad_report_logged = true;
            spdlog::warn(
                "usb input: {}: report rejected ({}; {} bytes, first byte 0x{:02x}); further ones are only counted",
                d.key, report_verdict_name(v), t.actual_length, t.actual_length > 0 ? t.buffer[0] : 0);
        }
    }
}

void UsbInput::Impl::resubmit(Device& d) {
    const int rc = libusb_submit_transfer(d.transfer);
    if (rc == 0) {
        d.in_flight = true;
    } else if (rc == LIBUSB_ERROR_NO_DEVICE) {
        begin_close(d, "unplugged");
    } else {
        bump(&UsbInputCounters::transfer_errors);
        begin_close(d, std::string("cannot resubmit the transfer: ") + libusb_error_name(rc));
    }
}

void LIBUSB_CALL UsbInput::Impl::on_transfer(libusb_transfer* t) {
    Device& d = *static_cast<Device*>(t->user_data);
    Impl& self = *d.owner;
    d.in_flight = false;
    if (d.closing) return;  // cancelled (or ended) while closing: finish_closing takes over
    switch (t->status) {
        case LIBUSB_TRANSFER_COMPLETED:
            d.consecutive_errors = 0;
            self.on_report(d, *t);
            self.resubmit(d);
            return;
        case LIBUSB_TRANSFER_NO_DEVICE:
            self.begin_close(d, "unplugged");
            return;
        case LIBUSB_TRANSFER_TIMED_OUT:  // no timeout is set; harmless
            self.resubmit(d);
            return;
        case LIBUSB_TRANSFER_CANCELLED:
            self.begin_close(d, "transfer cancelled");
            return;
        default:  // ERROR, STALL, OVERFLOW
            self.bump(&UsbInputCounters::transfer_errors);
            if (++d.consecutive_errors >= 20) {
                // Not reopened at every rescan: only after a replug (a new device node).
                self.refused[d.where] = Refusal{true, stamp_of(devnode_path(d.where.bus, d.where.address))};
                self.begin_close(d,
                                 std::string("20 transfer errors in a row, the last: ") + libusb_error_name(t->status));
                return;
            }
            if (t->status == LIBUSB_TRANSFER_STALL) spdlog::debug("usb input: {}: endpoint stalled", d.key);
            self.resubmit(d);
            return;
    }
}

// ---- closing ----------------------------------------------------------------------------------

// The device stops counting in the hub at once; the libusb side is released by finish_closing
// once the transfer is back.
void UsbInput::Impl::begin_close(Device& d, const std::string& reason) {
    if (d.closing) return;
    d.closing = true;
    d.close_reason = reason;
    d.close_deadline_ns = monotonic_ns() + 1000000000ull;
    hub.remove(d.key);
    {
        std::lock_guard lock(mutex);
        keys.erase(std::remove(keys.begin(), keys.end(), d.key), keys.end());
    }
    if (d.in_flight) libusb_cancel_transfer(d.transfer);
}

void UsbInput::Impl::finish_closing(bool force) {
    const uint64_t now = monotonic_ns();
    for (auto it = devices.begin(); it != devices.end();) {
        Device& d = **it;
        if (!d.closing || (d.in_flight && !force && now < d.close_deadline_ns)) {
            ++it;
            continue;
        }
        if (d.claimed) libusb_release_interface(d.handle, d.interface_number);  // reattaches the kernel driver
        libusb_close(d.handle);  // also drops a transfer that never came back
        // libusb forbids freeing a transfer still in flight: one that never came back is leaked.
        if (!d.in_flight)
            libusb_free_transfer(d.transfer);
        else
            spdlog::warn("usb input: {}: a transfer did not come back after cancel; left allocated", d.key);
        if (d.own_fd >= 0) ::close(d.own_fd);
        bump(&UsbInputCounters::devices_closed);
        spdlog::info("usb input: released {} \"{}\" ({})", d.model->name, d.key, d.close_reason);
        it = devices.erase(it);
    }
}

// ---- finding devices --------------------------------------------------------------------------

int LIBUSB_CALL UsbInput::Impl::on_hotplug(libusb_context*, libusb_device* dev, libusb_hotplug_event event,
                                           void* self) {
    Impl& impl = *static_cast<Impl*>(self);
    if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED) {
        impl.arrived.push_back(libusb_ref_device(dev));
    } else if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT) {
        impl.departed.push_back({libusb_get_bus_number(dev), libusb_get_device_address(dev)});
    }
    return 0;  // stay registered
}

void UsbInput::Impl::handle_hotplug_queue() {
    for (const BusAddress& where : std::exchange(departed, {})) {
        for (auto& d : devices)
            if (d->where == where) begin_close(*d, "unplugged");
        refused.erase(where);
    }
    for (libusb_device* dev : std::exchange(arrived, {})) {
        open_listed(dev);
        libusb_unref_device(dev);
    }
}

void UsbInput::Impl::rescan() {
    std::set<BusAddress> listed;
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx, &list);
    for (ssize_t i = 0; i < n; ++i) {
        listed.insert({libusb_get_bus_number(list[i]), libusb_get_device_address(list[i])});
        open_listed(list[i]);
    }
    if (n >= 0) libusb_free_device_list(list, 1);

    std::set<BusAddress> present = listed;
    if (opts.sysfs_rescan) {
        std::set<BusAddress> in_sysfs;
        scan_sysfs(listed, in_sysfs);
        sysfs_seen = in_sysfs;
        present.insert(in_sysfs.begin(), in_sysfs.end());
    }
    // Forget refusals of devices that are gone (their address may come back as another device).
    for (auto it = refused.begin(); it != refused.end();)
        it = present.count(it->first) ? std::next(it) : refused.erase(it);
}

void UsbInput::Impl::run() {
    if (opts.hotplug && libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) {
        const int rc = libusb_hotplug_register_callback(
            ctx,
            static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED | LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
            LIBUSB_HOTPLUG_NO_FLAGS, LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY,
            &Impl::on_hotplug, this, &hotplug_handle);
        hotplug_registered = rc == 0;
        if (rc != 0) spdlog::warn("usb input: no hotplug events ({}); rescanning only", libusb_error_name(rc));
    }
    spdlog::info("usb input: watching for {} navigation device models (hotplug events: {}; rescan every {} ms)",
                 table.size(), hotplug_registered ? "yes" : "no", opts.rescan_interval.count());
    rescan();
    auto next_rescan = std::chrono::steady_clock::now() + opts.rescan_interval;
    while (!stopping.load()) {
        timeval tv{0, 100000};
        const int rc = libusb_handle_events_timeout_completed(ctx, &tv, nullptr);
        if (rc != 0 && rc != LIBUSB_ERROR_INTERRUPTED) {
            if (!event_error_logged) spdlog::warn("usb input: libusb event handling: {}", libusb_error_name(rc));
            event_error_logged = true;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        handle_hotplug_queue();
        finish_closing(false);
        if (std::chrono::steady_clock::now() >= next_rescan) {
            rescan();
            next_rescan = std::chrono::steady_clock::now() + opts.rescan_interval;
        }
    }

    // Shut down: cancel every transfer, give them a moment to come back, release everything.
    for (auto& d : devices) begin_close(*d, "stopping");
    const uint64_t deadline = monotonic_ns() + 1000000000ull;
    auto any_in_flight = [&] {
        return std::any_of(devices.begin(), devices.end(), [](const auto& d) { return d->in_flight; });
    };
    while (any_in_flight() && monotonic_ns() < deadline) {
        timeval tv{0, 10000};
        libusb_handle_events_timeout_completed(ctx, &tv, nullptr);
    }
    finish_closing(true);
    if (hotplug_registered) libusb_hotplug_deregister_callback(ctx, hotplug_handle);
    hotplug_registered = false;
    for (libusb_device* dev : std::exchange(arrived, {})) libusb_unref_device(dev);
    departed.clear();
}

// ---- the public side --------------------------------------------------------------------------

UsbInput::UsbInput(std::vector<DeviceModel> table, InputHub& hub, UsbInputOptions opts)
    : impl_(std::make_unique<Impl>(std::move(table), hub, opts)) {}

UsbInput::~UsbInput() { stop(); }

bool UsbInput::start() {
    Impl& impl = *impl_;
    if (impl.thread.joinable()) return true;
    if (const int rc = libusb_init(&impl.ctx); rc != 0) {
        impl.ctx = nullptr;
        spdlog::warn("usb input: libusb cannot start ({}); running without USB navigation devices",
                     libusb_error_name(rc));
        return false;
    }
    impl.stopping = false;
    impl.thread = std::thread([&impl] { impl.run(); });
    return true;
}

void UsbInput::stop() {
    Impl& impl = *impl_;
    if (!impl.thread.joinable()) return;
    impl.stopping = true;
    libusb_interrupt_event_handler(impl.ctx);
    impl.thread.join();
    libusb_exit(impl.ctx);
    impl.ctx = nullptr;
}

UsbInputCounters UsbInput::counters() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->totals;
}

std::vector<std::string> UsbInput::open_devices() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->keys;
}

}  // namespace cupola

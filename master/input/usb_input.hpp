#pragma once
// Navigation devices on the master's USB ports, read through libusb-1.0 on one event thread.
//
// For every device in the device table that is plugged in, UsbInput opens it, claims its HID
// interface (the kernel's driver is detached while we hold it and reattached when we let go),
// keeps one asynchronous interrupt-IN transfer in flight, parses every report with the model's
// layout and publishes the device's NavSample to the InputHub under a stable key
// ("usb 1-4 046d:c626": bus-port path and ids, the same after a replug into the same port).
//
// Devices come and go during a show: libusb's hotplug events are used where libusb has them,
// and a rescan every UsbInputOptions::rescan_interval catches what the events missed. The rescan
// asks libusb for its device list and also looks in /sys/bus/usb/devices for table devices that
// libusb was never told about (no udev daemon, e.g. in a container, means no hotplug events);
// those are opened through their /dev/bus/usb node (libusb_wrap_sys_device) once they have been
// in /sys for a whole rescan interval (so that udev, where it runs, has set the node's
// permissions and told libusb first). An unplugged device
// is removed from the hub at once (the camera stops rather than drifts) and released.
//
// A device the master may not open (no write access to /dev/bus/usb/BBB/DDD) is logged once
// with the fix (the udev rule in configs/udev/) and counted; it is tried again only when its
// device node changes (a replug, or udev applying the rule). Without libusb, or without any
// device, the master runs on.
#include <chrono>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "input/device_table.hpp"
#include "input/input_hub.hpp"

namespace cupola {

struct UsbInputOptions {
    std::chrono::milliseconds rescan_interval{1000};  // how often to look for devices the events missed
    bool hotplug = true;                              // use libusb's hotplug events where libusb supports them
    bool sysfs_rescan = true;  // the rescan also opens table devices found only in /sys (see above)
};

struct UsbInputCounters {
    uint64_t devices_opened = 0;   // devices claimed and reading
    uint64_t devices_closed = 0;   // of those: released again (unplugged, failed, or stop())
    uint64_t reports = 0;          // interrupt-IN reports received
    uint64_t bad_reports = 0;      // of those: rejected by the layout (too short, unknown report id)
    uint64_t transfer_errors = 0;  // transfers that ended in an error other than an unplug
    uint64_t access_denied = 0;    // devices we may not open (permissions of the device node)
    uint64_t open_failures = 0;    // devices that failed to open or claim for another reason

    nlohmann::json to_json() const;
};

// The one error logged for a device we may not open: model, vid:pid, bus/address, device node
// and the udev rule that fixes it.
std::string usb_access_denied_message(const DeviceModel& model, int bus, int address);

class UsbInput {
public:
    UsbInput(std::vector<DeviceModel> table, InputHub& hub, UsbInputOptions opts = {});
    ~UsbInput();  // stop()
    UsbInput(const UsbInput&) = delete;
    UsbInput& operator=(const UsbInput&) = delete;

    // Starts libusb and the event thread, which opens the devices already plugged in. Returns
    // false (and logs why) when libusb cannot start; the master carries on without USB input.
    bool start();
    // Releases every device (reattaching kernel drivers), removes them from the hub, stops the
    // thread and libusb. Idempotent.
    void stop();

    UsbInputCounters counters() const;
    std::vector<std::string> open_devices() const;  // hub keys of the devices being read

private:
    struct Impl;  // the libusb side and the event thread (usb_input.cpp)
    std::unique_ptr<Impl> impl_;
};

}  // namespace cupola

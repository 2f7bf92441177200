#pragma once
// The meeting point of the USB thread and the master's frame loop: each device publishes its
// latest sample; the frame loop reads the combination once per frame. Thread-safe.
#include <algorithm>
#include <map>
#include <mutex>
#include <string>

#include "nav_input.hpp"

namespace cupola {

class InputHub {
public:
    // A device's newest state (key: a stable id of the device, e.g. "bus 1 addr 4").
    void publish(const std::string& key, const NavSample& s) {
        std::lock_guard lock(mutex_);
        samples_[key] = s;
    }
    // The device is gone: its axes stop counting at once (the camera stops, it does not drift).
    void remove(const std::string& key) {
        std::lock_guard lock(mutex_);
        samples_.erase(key);
    }
    // All connected devices together: axes summed and clamped to -1..1, buttons or-ed, the newest
    // report time and the sum of reports. connected is false when no device is connected.
    NavSample combined() const {
        std::lock_guard lock(mutex_);
        NavSample out;
        auto add = [](double& a, double b) { a = std::clamp(a + b, -1.0, 1.0); };
        for (const auto& [key, s] : samples_) {
            if (!s.connected) continue;
            out.connected = true;
            add(out.axes.right, s.axes.right);
            add(out.axes.up, s.axes.up);
            add(out.axes.forward, s.axes.forward);
            add(out.axes.pitch_up, s.axes.pitch_up);
            add(out.axes.yaw_left, s.axes.yaw_left);
            add(out.axes.roll_ccw, s.axes.roll_ccw);
            out.buttons |= s.buttons;
            out.report_ns = std::max(out.report_ns, s.report_ns);
            out.reports += s.reports;
            out.device = out.device.empty() ? s.device : out.device + "+" + s.device;
        }
        return out;
    }
    size_t connected_devices() const {
        std::lock_guard lock(mutex_);
        size_t n = 0;
        for (const auto& [key, s] : samples_) n += s.connected ? 1 : 0;
        return n;
    }

private:
    mutable std::mutex mutex_;
    std::map<std::string, NavSample> samples_;
};

}  // namespace cupola

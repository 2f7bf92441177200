#pragma once
// What a navigation device says, device-independent: six axes and the buttons, normalised so
// that every device drives the same navigation model. The USB layer (usb_input) produces these;
// the navigation model (navigation/) consumes them after dead zones and smoothing
// (navigation/input_shaper).
//
// Axes are in the camera's frame (the camera looks along -Z, +Y is up, +X is right):
//   right, up, forward      translation wish, -1..1 (forward = along the view direction, -Z)
//   pitch_up, yaw_left,     rotation wish, -1..1, right-handed about the camera's +X, +Y and +Z
//   roll_ccw                (pitch_up raises the view, yaw_left turns it left, roll_ccw rolls the
//                           camera counter-clockwise, so the picture turns clockwise)
// 0 is rest; a device that is not deflected gives 0 (before the dead zone: about 0).
#include <cstdint>
#include <string>

namespace cupola {

struct NavAxes {
    double right = 0.0, up = 0.0, forward = 0.0;
    double pitch_up = 0.0, yaw_left = 0.0, roll_ccw = 0.0;
    bool operator==(const NavAxes&) const = default;
};

struct NavSample {
    NavAxes axes;
    uint32_t buttons = 0;    // bit i: button i held
    bool connected = false;  // false: no device (unplugged or never found); axes are then 0
    uint64_t report_ns = 0;  // monotonic_ns() when the newest report in this sample arrived (0: none)
    uint64_t reports = 0;    // reports folded into this sample since the device was opened
    std::string device;      // model name from the device table ("" when none)
};

}  // namespace cupola

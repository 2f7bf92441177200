#pragma once
// The navigation devices the master knows: USB vendor/product id, what kind of device it is, and
// where its reports put the axes (hid_report_layout). default_device_table() covers common 3D
// mice and gamepads; a JSON file (format: configs/schema/devices.schema.json; example:
// configs/input/devices.json) can add models or replace a default one with the same
// vendor:product id.
//
// Axis signs of the defaults (NavAxes is in the camera frame: right, up, forward; pitch_up,
// yaw_left, roll_ccw right-handed about the camera's +X, +Y, +Z):
//   3D mouse (3Dconnexion HID frame: X right, Y toward the user, Z down; rotations right-handed
//   about those axes; full deflection about ±350):
//     push the cap right -> right = +x          push it away from you -> forward = -y
//     pull it up        -> up = -z              tilt it back (front edge up) -> pitch_up = +rx
//     twist it clockwise seen from above -> yaw_left = -rz (turns right)
//     tilt it to the left (left edge down) -> roll_ccw = +ry (the camera's up tips left)
//   Gamepad (sticks: 0 = left/up, 255 = right/down, 128 = rest):
//     left stick right -> right = +1            left stick up -> forward = +1
//     right stick right -> yaw_left = -1 (turn right)   right stick up -> pitch_up = +1 (look up)
//     right trigger -> up = +1, left trigger -> up = -1
// These follow the HID usage conventions; a device that differs is fixed with a file entry
// (scale -1 on the field).
#include <cstdint>
#include <string>
#include <vector>

#include "input/hid_report_layout.hpp"

namespace cupola {

enum class DeviceKind { SpaceMouse, Gamepad };

const char* device_kind_name(DeviceKind kind);  // "spacemouse", "gamepad"

struct DeviceModel {
    std::string name;  // shown in logs and NavSample::device
    uint16_t vendor_id = 0;
    uint16_t product_id = 0;
    DeviceKind kind = DeviceKind::SpaceMouse;
    HidReportLayout layout;
    int interface_number = -1;  // USB interface to claim; -1: the first HID interface (class 3)
                                // with an interrupt-IN endpoint
};

// "046d:c626"
std::string usb_id_string(uint16_t vendor_id, uint16_t product_id);

// The built-in models (3Dconnexion 3D mice, Logitech Dual Action / F310 in DirectInput mode,
// Sony DualShock 4).
std::vector<DeviceModel> default_device_table();

// The models in a device-table file (only those; see merge_device_tables). Throws ConfigError
// naming the file and the JSON path of the first problem.
std::vector<DeviceModel> load_device_table(const std::string& json_file);

// first, then every model of `rest` whose vendor:product id is not in `first` (file entries
// override defaults: merge_device_tables(load_device_table(f), default_device_table())).
std::vector<DeviceModel> merge_device_tables(std::vector<DeviceModel> first, const std::vector<DeviceModel>& rest);

// The model for a vendor:product id, or nullptr.
const DeviceModel* find_device_model(const std::vector<DeviceModel>& table, uint16_t vendor_id, uint16_t product_id);

}  // namespace cupola

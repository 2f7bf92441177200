#include "input/device_table.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>

#include "config/config_schema.hpp"
#include "config/json_reader.hpp"

namespace cupola {

namespace {

// ---- building blocks of the default layouts -------------------------------------------------

HidField axis_field(uint32_t bit_offset, uint32_t bits, bool is_signed, NavAxis axis, double centre, double half_range,
                    double scale) {
    HidField f;
    f.target = HidField::Target::Axis;
    f.bit_offset = bit_offset;
    f.bit_size = bits;
    f.is_signed = is_signed;
    f.axis = axis;
    f.centre = centre;
    f.half_range = half_range;
    f.scale = scale;
    return f;
}

HidField button_field(uint32_t bit_offset, uint32_t bits, uint32_t first_button) {
    HidField f;
    f.target = HidField::Target::Buttons;
    f.bit_offset = bit_offset;
    f.bit_size = bits;
    f.first_button = first_button;
    return f;
}

// 3Dconnexion 3D mice. Report 1: translation x, y, z (int16 LE at bytes 1, 3, 5); newer devices
// append rotation rx, ry, rz (bytes 7, 9, 11) to the same report, older ones (SpaceNavigator,
// SpaceExplorer) send the rotation as report 2. Report 3: button bitmask (2 bytes on most
// models, 4 on the SpacePilot Pro). Report 0x17: battery state of the wireless models (ignored).
HidReportLayout spacemouse_layout(double range) {
    HidReportLayout l;
    l.report_ids = true;
    // signs: see device_table.hpp
    HidReport translation{1, 7, {}};
    translation.fields = {
        axis_field(8, 16, true, NavAxis::Right, 0, range, +1.0),
        axis_field(24, 16, true, NavAxis::Forward, 0, range, -1.0),
        axis_field(40, 16, true, NavAxis::Up, 0, range, -1.0),
        // present only in the 13-byte form of report 1
        axis_field(56, 16, true, NavAxis::PitchUp, 0, range, +1.0),
        axis_field(72, 16, true, NavAxis::RollCcw, 0, range, +1.0),
        axis_field(88, 16, true, NavAxis::YawLeft, 0, range, -1.0),
    };
    HidReport rotation{2, 7, {}};
    rotation.fields = {
        axis_field(8, 16, true, NavAxis::PitchUp, 0, range, +1.0),
        axis_field(24, 16, true, NavAxis::RollCcw, 0, range, +1.0),
        axis_field(40, 16, true, NavAxis::YawLeft, 0, range, -1.0),
    };
    HidReport buttons{3, 2, {}};
    for (uint32_t b = 0; b < 4; ++b) buttons.fields.push_back(button_field(8 + 8 * b, 8, 8 * b));
    HidReport battery{0x17, 1, {}};
    l.reports = {translation, rotation, buttons, battery};
    return l;
}

// The four stick fields of a gamepad whose sticks are uint8 centred at 128, starting at byte
// `first` in the order LX, LY, RX, RY. Left stick: strafe/walk; right stick: look.
std::vector<HidField> gamepad_sticks(uint32_t first) {
    const uint32_t b = first * 8;
    return {
        axis_field(b, 8, false, NavAxis::Right, 128, 127, +1.0),
        axis_field(b + 8, 8, false, NavAxis::Forward, 128, 127, -1.0),
        axis_field(b + 16, 8, false, NavAxis::YawLeft, 128, 127, -1.0),
        axis_field(b + 24, 8, false, NavAxis::PitchUp, 128, 127, -1.0),
    };
}

// Logitech Dual Action, and the F310/F510/F710 in DirectInput mode (switch at the back on "D"):
// 8 bytes, no report id. Bytes 0..3 LX, LY, RX, RY; byte 4 bits 0..3 the hat (ignored), bits
// 4..15 buttons 1..12 (5 LB, 6 RB, 7 LT, 8 RT). The digital triggers move up (RT) and down (LT).
HidReportLayout logitech_dinput_layout() {
    HidReportLayout l;
    l.report_ids = false;
    HidReport r{0, 6, gamepad_sticks(0)};
    r.fields.push_back(button_field(36, 12, 0));
    r.fields.push_back(axis_field(43, 1, false, NavAxis::Up, 0, 1, +1.0));  // RT (button 8)
    r.fields.push_back(axis_field(42, 1, false, NavAxis::Up, 0, 1, -1.0));  // LT (button 7)
    l.reports = {r};
    return l;
}

// Sony DualShock 4 over USB: report 1, 64 bytes. Bytes 1..4 LX, LY, RX, RY; byte 5 bits 0..3
// the hat (ignored), bits 4..7 square, cross, circle, triangle; byte 6 L1 R1 L2 R2 share options
// L3 R3; byte 7 bit 0 PS, bit 1 touchpad click; bytes 8, 9 the analog L2, R2 (0..255).
HidReportLayout dualshock4_layout() {
    HidReportLayout l;
    l.report_ids = true;
    HidReport r{1, 10, gamepad_sticks(1)};
    r.fields.push_back(button_field(44, 4, 0));
    r.fields.push_back(button_field(48, 8, 4));
    r.fields.push_back(button_field(56, 2, 12));
    r.fields.push_back(axis_field(64, 8, false, NavAxis::Up, 0, 255, -1.0));  // L2 down
    r.fields.push_back(axis_field(72, 8, false, NavAxis::Up, 0, 255, +1.0));  // R2 up
    l.reports = {r};
    return l;
}

DeviceModel model(std::string name, uint16_t vid, uint16_t pid, DeviceKind kind, HidReportLayout layout) {
    DeviceModel m;
    m.name = std::move(name);
    m.vendor_id = vid;
    m.product_id = pid;
    m.kind = kind;
    m.layout = std::move(layout);
    return m;
}

// ---- reading a device-table file -------------------------------------------------------------
// Defaults and ranges of every field: configs/schema/devices.schema.json (JsonReader::declared_*).
// What a schema cannot say is checked here: button fields past button 31, unsigned buttons,
// logical_max above logical_min, a non-zero half_range, the layout as a whole (layout_problem)
// and unique report ids and vendor:product ids.

uint16_t usb_id(const JsonReader& r, const std::string& key) {
    const std::string s = r.string(key);
    bool ok = s.size() == 4;
    for (char c : s) ok = ok && std::isxdigit(static_cast<unsigned char>(c));
    if (!ok) r.fail(key, "\"" + s + "\" is not a USB id of 4 hex digits (like \"046d\")");
    return static_cast<uint16_t>(std::stoul(s, nullptr, 16));
}

HidField read_field(const JsonReader& r) {
    HidField f;
    f.bit_offset = static_cast<uint32_t>(r.declared_integer("bit_offset"));
    f.bit_size = static_cast<uint32_t>(r.declared_integer("bits"));
    f.is_signed = r.declared_boolean("signed");
    const bool is_axis = r.has("axis"), is_buttons = r.has("first_button");
    if (is_axis == is_buttons) r.fail("axis", "a field has either \"axis\" or \"first_button\", not both or neither");
    if (is_buttons) {
        f.target = HidField::Target::Buttons;
        f.first_button = static_cast<uint32_t>(r.required_integer("first_button"));
        if (f.first_button + f.bit_size > 32) r.fail("bits", "buttons would go past button 31");
        if (f.is_signed) r.fail("signed", "a button field is not signed");
    } else {
        f.target = HidField::Target::Axis;
        f.axis = *nav_axis_from_name(r.one_of("axis", r.declared_choices("axis")));
        const bool by_centre = r.has("centre") || r.has("half_range");
        const bool by_limits = r.has("logical_min") || r.has("logical_max");
        if (by_centre == by_limits)
            r.fail("half_range", "give either \"centre\" and \"half_range\" or \"logical_min\" and \"logical_max\"");
        if (by_centre) {
            f.centre = r.number("centre", r.declaration("centre").at("default").get<double>());
            f.half_range = r.number("half_range");
        } else {
            const double lo = r.number("logical_min"), hi = r.number("logical_max");
            if (!(hi > lo)) r.fail("logical_max", "must be greater than logical_min");
            f.centre = (lo + hi) / 2;
            f.half_range = (hi - lo) / 2;
        }
        if (f.half_range == 0.0) r.fail("half_range", "must not be 0");
        f.scale = r.number("scale", r.declaration("scale").at("default").get<double>());
    }
    r.reject_unknown_keys();
    return f;
}

HidReport read_report(const JsonReader& r, bool report_ids) {
    HidReport rep;
    if (report_ids) rep.id = static_cast<uint8_t>(r.required_integer("id"));
    for (const auto& fr : r.array("fields")) rep.fields.push_back(read_field(fr));
    size_t needed = 1;
    for (const auto& f : rep.fields) needed = std::max(needed, f.end_byte());
    // Default: every field must be there; a smaller min_bytes makes the later fields optional.
    rep.min_bytes = static_cast<size_t>(r.declared_integer("min_bytes", static_cast<long long>(needed)));
    r.reject_unknown_keys();
    return rep;
}

DeviceModel read_model(const JsonReader& r) {
    DeviceModel m;
    m.name = r.declared_string("name");
    if (m.name.empty()) r.fail("name", "must not be empty");
    m.vendor_id = usb_id(r, "vendor_id");
    m.product_id = usb_id(r, "product_id");
    m.kind = r.declared_choice("kind") == "gamepad" ? DeviceKind::Gamepad : DeviceKind::SpaceMouse;
    m.interface_number = static_cast<int>(r.declared_integer("interface"));
    m.layout.report_ids = r.declared_boolean("report_ids");
    const auto reports = r.array("reports");
    if (reports.empty()) r.fail("reports", "at least one report is needed");
    if (!m.layout.report_ids && reports.size() != 1)
        r.fail("reports", "a device without report ids (\"report_ids\": false) has exactly one report");
    std::set<int> ids;
    for (const auto& rr : reports) {
        m.layout.reports.push_back(read_report(rr, m.layout.report_ids));
        if (m.layout.report_ids && !ids.insert(m.layout.reports.back().id).second)
            rr.fail("id", "report id " + std::to_string(m.layout.reports.back().id) + " appears twice");
    }
    const std::string problem = layout_problem(m.layout);
    if (!problem.empty()) r.fail("reports", problem);
    r.reject_unknown_keys();
    return m;
}

}  // namespace

const char* device_kind_name(DeviceKind kind) { return kind == DeviceKind::Gamepad ? "gamepad" : "spacemouse"; }

std::string usb_id_string(uint16_t vendor_id, uint16_t product_id) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%04x:%04x", vendor_id, product_id);
    return buf;
}

std::vector<DeviceModel> default_device_table() {
    const auto sm = DeviceKind::SpaceMouse;
    const auto gp = DeviceKind::Gamepad;
    const HidReportLayout mouse = spacemouse_layout(350.0);
    return {
        // Logitech-era 3Dconnexion (vendor 046d): translation and rotation in reports 1 and 2.
        model("3Dconnexion SpaceNavigator", 0x046d, 0xc626, sm, mouse),
        model("3Dconnexion SpaceExplorer", 0x046d, 0xc627, sm, mouse),
        model("3Dconnexion SpaceNavigator for Notebooks", 0x046d, 0xc628, sm, mouse),
        model("3Dconnexion SpacePilot Pro", 0x046d, 0xc629, sm, mouse),
        model("3Dconnexion SpaceMouse Pro", 0x046d, 0xc62b, sm, mouse),
        // 3Dconnexion's own vendor id (256f): all six axes in report 1.
        model("3Dconnexion SpaceMouse Wireless (cable)", 0x256f, 0xc62e, sm, mouse),
        model("3Dconnexion SpaceMouse Wireless (receiver)", 0x256f, 0xc62f, sm, mouse),
        model("3Dconnexion SpaceMouse Pro Wireless (cable)", 0x256f, 0xc631, sm, mouse),
        model("3Dconnexion SpaceMouse Pro Wireless (receiver)", 0x256f, 0xc632, sm, mouse),
        model("3Dconnexion SpaceMouse Enterprise", 0x256f, 0xc633, sm, mouse),
        model("3Dconnexion SpaceMouse Compact", 0x256f, 0xc635, sm, mouse),
        model("3Dconnexion Universal Receiver", 0x256f, 0xc652, sm, mouse),
        // Gamepads.
        model("Logitech Dual Action / F310 (DirectInput)", 0x046d, 0xc216, gp, logitech_dinput_layout()),
        model("Sony DualShock 4", 0x054c, 0x05c4, gp, dualshock4_layout()),
        model("Sony DualShock 4 (2nd generation)", 0x054c, 0x09cc, gp, dualshock4_layout()),
    };
}

std::vector<DeviceModel> load_device_table(const std::string& json_file) {
    const nlohmann::json doc = JsonReader::parse_file(json_file);
    const JsonReader top(doc, json_file, &config_schema("devices"));
    std::vector<DeviceModel> out;
    std::set<uint32_t> seen;
    const auto devices = top.array("devices");
    for (const auto& d : devices) {
        DeviceModel m = read_model(d);
        if (!seen.insert(uint32_t{m.vendor_id} << 16 | m.product_id).second)
            d.fail("product_id", usb_id_string(m.vendor_id, m.product_id) + " appears twice in this file");
        out.push_back(std::move(m));
    }
    top.reject_unknown_keys();
    return out;
}

std::vector<DeviceModel> merge_device_tables(std::vector<DeviceModel> first, const std::vector<DeviceModel>& rest) {
    for (const auto& m : rest)
        if (find_device_model(first, m.vendor_id, m.product_id) == nullptr) first.push_back(m);
    return first;
}

const DeviceModel* find_device_model(const std::vector<DeviceModel>& table, uint16_t vendor_id, uint16_t product_id) {
    for (const auto& m : table)
        if (m.vendor_id == vendor_id && m.product_id == product_id) return &m;
    return nullptr;
}

}  // namespace cupola

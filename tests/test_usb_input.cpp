// USB navigation devices on the master (master/input/): the report parser on both 3D-mouse
// protocols and on gamepads, the device table and its file, the udev rule, and UsbInput against
// emulated devices: libusb enumerates them from a umockdev testbed, opens them, claims their
// HID interface and reads interrupt-IN reports through the real usbdevfs ioctls (the device
// side is tests/support/umockdev_devices.hpp). This executable runs under umockdev-wrapper.
#include <gtest/gtest.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "config/config_error.hpp"
#include "input/device_table.hpp"
#include "input/hid_report_layout.hpp"
#include "input/input_hub.hpp"
#include "input/usb_input.hpp"
#include "support/test_support.hpp"
#include "support/umockdev_devices.hpp"
#include "util/monotonic_clock.hpp"

using namespace cupola;
using namespace std::chrono_literals;

namespace {

const DeviceModel& model_for(uint16_t vid, uint16_t pid) {
    static const std::vector<DeviceModel> table = default_device_table();
    const DeviceModel* m = find_device_model(table, vid, pid);
    if (m == nullptr) throw std::runtime_error("no default model " + usb_id_string(vid, pid));
    return *m;
}

ReportVerdict apply(const DeviceModel& m, const std::vector<uint8_t>& report, NavSample& s) {
    // An exactly sized heap copy: a read past the end would be a read past the allocation.
    std::unique_ptr<uint8_t[]> copy(new uint8_t[std::max<size_t>(report.size(), 1)]);
    std::copy(report.begin(), report.end(), copy.get());
    return apply_report(m.layout, copy.get(), report.size(), s);
}

constexpr double kEps = 1e-9;

void expect_axes(const NavAxes& a, double right, double up, double forward, double pitch_up, double yaw_left,
                 double roll_ccw) {
    EXPECT_NEAR(a.right, right, kEps);
    EXPECT_NEAR(a.up, up, kEps);
    EXPECT_NEAR(a.forward, forward, kEps);
    EXPECT_NEAR(a.pitch_up, pitch_up, kEps);
    EXPECT_NEAR(a.yaw_left, yaw_left, kEps);
    EXPECT_NEAR(a.roll_ccw, roll_ccw, kEps);
}

}  // namespace

// ---- the report parser -------------------------------------------------------------------------

TEST(UsbReportParser, SpaceNavigatorSplitReportsUpdateOnlyWhatTheyCarry) {
    const DeviceModel& m = model_for(0x046d, 0xc626);
    NavSample s;
    // Report 1: x = +175 of 350 -> right 0.5; y = -175 (cap pushed away) -> forward +0.5;
    // z = -70 (cap pulled up) -> up +0.2.
    ASSERT_EQ(apply(m, test::spacemouse_report(1, 175, -175, -70), s), ReportVerdict::Applied);
    expect_axes(s.axes, 0.5, 0.2, 0.5, 0, 0, 0);
    // Report 2: rx = +35 (tilted back) -> pitch_up +0.1; ry = -105 (tilted right) -> roll_ccw -0.3;
    // rz = +350 (twisted clockwise) -> yaw_left -1. Translation stays as report 1 left it.
    ASSERT_EQ(apply(m, test::spacemouse_report(2, 35, -105, 350), s), ReportVerdict::Applied);
    expect_axes(s.axes, 0.5, 0.2, 0.5, 0.1, -1.0, -0.3);
    // A new report 1 replaces the translation only.
    ASSERT_EQ(apply(m, test::spacemouse_report(1, -350, 0, 0), s), ReportVerdict::Applied);
    expect_axes(s.axes, -1.0, 0, 0, 0.1, -1.0, -0.3);
    // At rest.
    apply(m, test::spacemouse_report(1, 0, 0, 0), s);
    apply(m, test::spacemouse_report(2, 0, 0, 0), s);
    EXPECT_EQ(s.axes, NavAxes{});
}

TEST(UsbReportParser, SpaceMouseSixAxisReportCarriesTranslationAndRotation) {
    const DeviceModel& m = model_for(0x256f, 0xc635);
    NavSample s;
    ASSERT_EQ(apply(m, test::spacemouse_report6(350, 70, -35, -350, 175, -175), s), ReportVerdict::Applied);
    // right +1, forward -0.2 (pulled toward the user), up +0.1, pitch_up -1, roll_ccw +0.5, yaw_left +0.5
    expect_axes(s.axes, 1.0, 0.1, -0.2, -1.0, 0.5, 0.5);
    // The same model also accepts the 7-byte form: the rotation is then not carried and stays.
    ASSERT_EQ(apply(m, test::spacemouse_report(1, 0, 0, 0), s), ReportVerdict::Applied);
    expect_axes(s.axes, 0, 0, 0, -1.0, 0.5, 0.5);
}

TEST(UsbReportParser, SpaceMouseButtonsAndIgnoredReports) {
    const DeviceModel& m = model_for(0x046d, 0xc626);
    NavSample s;
    ASSERT_EQ(apply(m, test::spacemouse_buttons(0x0102), s), ReportVerdict::Applied);
    EXPECT_EQ(s.buttons, 0x0102u);
    // A shorter report 3 carries only its first button byte; buttons 8..15 keep their state.
    ASSERT_EQ(apply(m, {3, 0x01}, s), ReportVerdict::Applied);
    EXPECT_EQ(s.buttons, 0x0101u);
    // The wireless models' battery report is known and ignored.
    const NavSample before = s;
    EXPECT_EQ(apply(m, {0x17, 0x64}, s), ReportVerdict::Ignored);
    EXPECT_EQ(s.buttons, before.buttons);
    EXPECT_EQ(s.axes, before.axes);
}

TEST(UsbReportParser, GamepadSticksAreCentredAndSigned) {
    const DeviceModel& pad = model_for(0x046d, 0xc216);
    NavSample s;
    // Every stick at 128: exactly 0.
    ASSERT_EQ(apply(pad, test::dual_action_report(128, 128, 128, 128), s), ReportVerdict::Applied);
    EXPECT_EQ(s.axes, NavAxes{});
    // Left stick right and up; right stick left and down (0 = left/up, 255 = right/down).
    ASSERT_EQ(apply(pad, test::dual_action_report(192, 64, 0, 255), s), ReportVerdict::Applied);
    expect_axes(s.axes, 64.0 / 127, 0, 64.0 / 127, -1.0, 1.0, 0);
    // Full deflection is clamped to 1 (0 is 128/127 from the centre).
    apply(pad, test::dual_action_report(255, 0, 128, 128), s);
    expect_axes(s.axes, 1.0, 0, 1.0, 0, 0, 0);
    // RT (button 8) moves up, LT (button 7) down; the buttons show too.
    apply(pad, test::dual_action_report(128, 128, 128, 128, 1u << 7), s);
    EXPECT_NEAR(s.axes.up, 1.0, kEps);
    EXPECT_EQ(s.buttons, 1u << 7);
    apply(pad, test::dual_action_report(128, 128, 128, 128, 1u << 6), s);
    EXPECT_NEAR(s.axes.up, -1.0, kEps);

    const DeviceModel& ds4 = model_for(0x054c, 0x05c4);
    NavSample d;
    ASSERT_EQ(apply(ds4, test::dualshock4_report(128, 128, 128, 128), d), ReportVerdict::Applied);
    EXPECT_EQ(d.axes, NavAxes{});
    // R2 fully pressed -> up +1; L2 at 51 of 255 -> down 0.2.
    apply(ds4, test::dualshock4_report(128, 128, 128, 128, 0, 255), d);
    EXPECT_NEAR(d.axes.up, 1.0, kEps);
    apply(ds4, test::dualshock4_report(128, 128, 128, 128, 51, 0), d);
    EXPECT_NEAR(d.axes.up, -0.2, kEps);
    // Right stick right -> turn right (yaw_left < 0); up -> look up.
    apply(ds4, test::dualshock4_report(128, 128, 255, 1), d);
    expect_axes(d.axes, 0, 0, 0, 1.0, -1.0, 0);
    // Cross (face bit 1) is button 1, L1 is button 4.
    apply(ds4, test::dualshock4_report(128, 128, 128, 128, 0, 0, 0b0010, 0b0001), d);
    EXPECT_EQ(d.buttons, (1u << 1) | (1u << 4));
}

TEST(UsbReportParser, ShortReportsAndUnknownIdsAreRejectedWithoutChange) {
    const DeviceModel& m = model_for(0x046d, 0xc626);
    NavSample s;
    apply(m, test::spacemouse_report(1, 100, 200, 300), s);
    const NavSample before = s;
    EXPECT_EQ(apply(m, {9, 1, 2, 3, 4, 5, 6}, s), ReportVerdict::UnknownId);
    EXPECT_EQ(apply(m, {}, s), ReportVerdict::TooShort);
    EXPECT_EQ(apply_report(m.layout, nullptr, 0, s), ReportVerdict::TooShort);
    // Every truncation of report 1 below its 7 bytes is refused (and read only inside the buffer).
    const auto full = test::spacemouse_report(1, 350, 350, 350);
    for (size_t n = 1; n < 7; ++n)
        EXPECT_EQ(apply(m, std::vector<uint8_t>(full.begin(), full.begin() + n), s), ReportVerdict::TooShort) << n;
    EXPECT_EQ(s.axes, before.axes);
    EXPECT_EQ(s.buttons, before.buttons);

    const DeviceModel& pad = model_for(0x046d, 0xc216);
    NavSample p;
    EXPECT_EQ(apply(pad, {128, 128, 128, 128, 8}, p), ReportVerdict::TooShort);
    const DeviceModel& ds4 = model_for(0x054c, 0x05c4);
    EXPECT_EQ(apply(ds4, {2, 0, 0, 0, 0, 0, 0, 0, 0, 0}, p), ReportVerdict::UnknownId);
    EXPECT_EQ(apply(ds4, {1, 0, 0, 0, 0}, p), ReportVerdict::TooShort);
    EXPECT_EQ(p.axes, NavAxes{});
}

// ---- the device table ----------------------------------------------------------------------------

TEST(UsbDeviceTable, DefaultsAreUsableAndUnique) {
    const auto table = default_device_table();
    std::set<std::string> ids;
    bool spacemouse = false, gamepad = false;
    for (const auto& m : table) {
        EXPECT_FALSE(m.name.empty());
        EXPECT_EQ(layout_problem(m.layout), "") << m.name;
        EXPECT_TRUE(ids.insert(usb_id_string(m.vendor_id, m.product_id)).second) << m.name;
        spacemouse |= m.kind == DeviceKind::SpaceMouse;
        gamepad |= m.kind == DeviceKind::Gamepad;
    }
    EXPECT_TRUE(spacemouse && gamepad);
    for (const char* id : {"046d:c626", "256f:c635", "256f:c62e", "046d:c629", "046d:c216", "054c:05c4", "054c:09cc"})
        EXPECT_TRUE(ids.count(id)) << id;
}

TEST(UsbDeviceTable, ExampleFileLoadsAndOverridesTheDefaults) {
    const std::string file = test::source_path("configs/input/devices.json");
    const auto from_file = load_device_table(file);
    ASSERT_EQ(from_file.size(), 2u);
    const auto defaults = default_device_table();
    const auto table = merge_device_tables(from_file, defaults);
    EXPECT_EQ(table.size(), defaults.size() + 1);  // the SpaceNavigator replaced, the DualSense added
    const DeviceModel* nav = find_device_model(table, 0x046d, 0xc626);
    ASSERT_NE(nav, nullptr);
    EXPECT_EQ(nav->name, "3Dconnexion SpaceNavigator (pitch inverted)");
    NavSample s;
    ASSERT_EQ(apply(*nav, test::spacemouse_report(2, 35, 0, 0), s), ReportVerdict::Applied);
    EXPECT_NEAR(s.axes.pitch_up, -0.1, kEps);  // the file's scale -1, via logical_min/max
    ASSERT_EQ(apply(*nav, test::spacemouse_report(1, 175, 0, 0), s), ReportVerdict::Applied);
    EXPECT_NEAR(s.axes.right, 0.5, kEps);
    const DeviceModel* sense = find_device_model(table, 0x054c, 0x0ce6);
    ASSERT_NE(sense, nullptr);
    EXPECT_EQ(sense->kind, DeviceKind::Gamepad);
    EXPECT_EQ(sense->interface_number, 3);
    EXPECT_EQ(sense->layout.reports.at(0).min_bytes, 11u);
}

TEST(UsbDeviceTable, BadFilesNameTheFileAndTheField) {
    const std::string dir = test::scratch_dir("usb_device_table");
    const std::string good_field =
        R"({"axis": "right", "bit_offset": 8, "bits": 16, "signed": true, "half_range": 350})";
    auto device = [](const std::string& fields, const std::string& extra = "") {
        return R"({"name": "m", "vendor_id": "046d", "product_id": "c626", "kind": "spacemouse", )" + extra +
               R"("reports": [{"id": 1, "fields": [)" + fields + "]}]}";
    };
    struct Case {
        std::string json, field, words;
    };
    const std::vector<Case> cases = {
        {R"({"devices": [{"name": "m", "vendor_id": "46d", "product_id": "c626", "kind": "spacemouse", "reports": []}]})",
         "devices[0].vendor_id", "4 hex digits"},
        {R"({"devices": [{"name": "m", "vendor_id": "046d", "product_id": "c626", "kind": "wand", "reports": []}]})",
         "devices[0].kind", "not one of"},
        {R"({"devices": [)" + device(R"({"axis": "sideways", "bit_offset": 8, "bits": 16, "half_range": 1})") + "]}",
         "devices[0].reports[0].fields[0].axis", "not one of"},
        {R"({"devices": [)" + device(R"({"axis": "up", "bit_offset": 8, "bits": 16, "half_range": 1, "scael": 2})") +
             "]}",
         "devices[0].reports[0].fields[0].scael", "unknown key"},
        {R"({"devices": [)" +
             device(R"({"axis": "up", "first_button": 0, "bit_offset": 8, "bits": 1, "half_range": 1})") + "]}",
         "devices[0].reports[0].fields[0].axis", "not both"},
        {R"({"devices": [)" + device(R"({"axis": "up", "bit_offset": 8, "bits": 40, "half_range": 1})") + "]}",
         "devices[0].reports[0].fields[0].bits", "outside the allowed range"},
        {R"({"devices": [)" + device(R"({"axis": "up", "bit_offset": 8, "bits": 8, "half_range": 0})") + "]}",
         "devices[0].reports[0].fields[0].half_range", "must not be 0"},
        {R"({"devices": [)" + device(R"({"axis": "up", "bit_offset": 8, "bits": 8})") + "]}",
         "devices[0].reports[0].fields[0].half_range", "either"},
        {R"({"devices": [{"name": "m", "vendor_id": "046d", "product_id": "c626", "kind": "spacemouse", "reports": [)"
         R"({"id": 1, "fields": []}, {"id": 1, "fields": []}]}]})",
         "devices[0].reports[1].id", "appears twice"},
        {R"({"devices": [)" + device(good_field) + ", " + device(good_field) + "]}", "devices[1].product_id",
         "appears twice"},
        {R"({"devices": [)" + device(good_field, R"("report_ids": false, )") + "]}", "devices[0].reports[0].id",
         "unknown key"},
        {R"({"devices": [)", "", "JSON syntax error"},
    };
    for (size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i];
        const std::string file = dir + "/devices_" + std::to_string(i) + ".json";
        test::write_text(file, c.json);
        try {
            load_device_table(file);
            ADD_FAILURE() << "accepted: " << c.json;
        } catch (const ConfigError& e) {
            EXPECT_EQ(e.file(), file);
            if (!c.field.empty()) {
                EXPECT_EQ(e.field(), c.field) << e.what();
            }
            EXPECT_NE(std::string(e.what()).find(c.words), std::string::npos) << e.what();
        }
    }
}

TEST(UsbDeviceTable, UdevRuleCoversEveryDefaultModel) {
    const std::string rules = test::read_text(test::source_path("configs/udev/70-cupola-navigation.rules"));
    const std::regex line_re(R"re(ATTR\{idVendor\}=="([0-9a-f]{4})", ATTR\{idProduct\}=="([0-9a-f]{4})")re");
    std::set<std::string> in_rule;
    std::istringstream in(rules);
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::smatch m;
        ASSERT_TRUE(std::regex_search(line, m, line_re)) << line;
        in_rule.insert(m[1].str() + ":" + m[2].str());
        EXPECT_NE(line.find(R"(SUBSYSTEM=="usb")"), std::string::npos) << line;
        EXPECT_NE(line.find(R"(MODE="0660")"), std::string::npos) << line;
        EXPECT_NE(line.find(R"(GROUP="plugdev")"), std::string::npos) << line;
        EXPECT_NE(line.find(R"(TAG+="uaccess")"), std::string::npos) << line;
    }
    std::set<std::string> known;
    for (const auto& m : default_device_table()) {
        const std::string id = usb_id_string(m.vendor_id, m.product_id);
        known.insert(id);
        EXPECT_TRUE(in_rule.count(id)) << m.name << " (" << id << ") has no line in the udev rule";
    }
    for (const auto& m : load_device_table(test::source_path("configs/input/devices.json")))
        known.insert(usb_id_string(m.vendor_id, m.product_id));
    for (const auto& id : in_rule) EXPECT_TRUE(known.count(id)) << id << " is in the udev rule but in no device table";
}

TEST(UsbInputMessages, AccessDeniedNamesTheDeviceNodeAndTheFix) {
    const std::string msg = usb_access_denied_message(model_for(0x046d, 0xc626), 3, 17);
    for (const char* part : {"3Dconnexion SpaceNavigator", "046d:c626", "bus 3 address 17", "/dev/bus/usb/003/017",
                             "sudo cp configs/udev/70-cupola-navigation.rules /etc/udev/rules.d/",
                             "sudo udevadm control --reload", "sudo udevadm trigger"})
        EXPECT_NE(msg.find(part), std::string::npos) << part << " missing from: " << msg;
}

// ---- UsbInput against emulated devices ------------------------------------------------------------

namespace {

// Collects what is logged (and still prints it), so a test can check what an operator would see.
class CaptureSink : public spdlog::sinks::base_sink<std::mutex> {
public:
    std::vector<std::string> lines() {
        std::lock_guard lock(mutex_);
        return lines_;
    }

protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {
        lines_.emplace_back(msg.payload.data(), msg.payload.size());
    }
    void flush_() override {}

private:
    std::vector<std::string> lines_;
};

size_t count_containing(const std::vector<std::string>& lines, const std::string& part) {
    return static_cast<size_t>(std::count_if(lines.begin(), lines.end(),
                                             [&](const std::string& l) { return l.find(part) != std::string::npos; }));
}

class UsbInputTest : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_TRUE(test::UsbTestbed::preloaded())
            << "run this test under umockdev-wrapper (ctest does): umockdev-wrapper bin/test_usb_input";
        previous_logger_ = spdlog::default_logger();
        capture_ = std::make_shared<CaptureSink>();
        auto logger = std::make_shared<spdlog::logger>(
            "usb-test", spdlog::sinks_init_list{capture_, std::make_shared<spdlog::sinks::stderr_sink_mt>()});
        logger->set_level(spdlog::level::info);
        spdlog::set_default_logger(logger);
        bed_ = std::make_unique<test::UsbTestbed>();
    }
    void TearDown() override {
        input_.reset();  // before the testbed it talks to
        bed_.reset();
        if (previous_logger_) spdlog::set_default_logger(previous_logger_);
    }

    static UsbInputOptions fast() {
        UsbInputOptions o;
        o.rescan_interval = 100ms;
        return o;
    }
    UsbInput& start(UsbInputOptions opts = fast()) {
        input_ = std::make_unique<UsbInput>(default_device_table(), hub_, opts);
        EXPECT_TRUE(input_->start());
        return *input_;
    }
    bool wait_open(size_t n, std::chrono::milliseconds timeout = 3000ms) {
        return test::wait_until([&] { return input_->open_devices().size() == n; }, timeout);
    }
    // Sends a report and waits until the hub has it (reports counts every applied report).
    bool send(test::EmulatedUsbDevice& dev, std::vector<uint8_t> report) {
        const uint64_t before = hub_.combined().reports;
        dev.send_report(std::move(report));
        return test::wait_until([&] { return hub_.combined().reports > before; });
    }

    std::unique_ptr<test::UsbTestbed> bed_;
    InputHub hub_;
    std::unique_ptr<UsbInput> input_;
    std::shared_ptr<CaptureSink> capture_;
    std::shared_ptr<spdlog::logger> previous_logger_;
};

}  // namespace

TEST_F(UsbInputTest, ReadsASpaceMouseThroughLibusb) {
    auto& mouse = bed_->add_device(test::space_navigator());
    UsbInput& in = start();
    ASSERT_TRUE(wait_open(1)) << "the SpaceNavigator was not opened";
    EXPECT_EQ(in.open_devices(), std::vector<std::string>{"usb 1-1 046d:c626"});
    // libusb claimed the interface after detaching the kernel's HID driver.
    EXPECT_EQ(mouse.claims(), 1);
    EXPECT_EQ(mouse.driver_detaches(), 1);
    EXPECT_FALSE(mouse.kernel_driver_bound());
    ASSERT_TRUE(test::wait_until([&] { return mouse.urbs_in_flight() == 1; })) << "no interrupt transfer submitted";
    NavSample s = hub_.combined();
    EXPECT_TRUE(s.connected);
    EXPECT_EQ(s.device, "3Dconnexion SpaceNavigator");
    EXPECT_EQ(s.reports, 0u);

    const uint64_t t0 = monotonic_ns();
    ASSERT_TRUE(send(mouse, test::spacemouse_report(1, 175, -175, -70)));
    s = hub_.combined();
    expect_axes(s.axes, 0.5, 0.2, 0.5, 0, 0, 0);
    EXPECT_GE(s.report_ns, t0);
    EXPECT_LE(s.report_ns, monotonic_ns());
    ASSERT_TRUE(send(mouse, test::spacemouse_report(2, 35, -105, 350)));
    expect_axes(hub_.combined().axes, 0.5, 0.2, 0.5, 0.1, -1.0, -0.3);
    ASSERT_TRUE(send(mouse, test::spacemouse_buttons(0x0003)));
    EXPECT_EQ(hub_.combined().buttons, 0x0003u);
    EXPECT_EQ(hub_.combined().reports, 3u);
    EXPECT_EQ(mouse.reports_delivered(), 3u);

    const UsbInputCounters c = in.counters();
    EXPECT_EQ(c.devices_opened, 1u);
    EXPECT_EQ(c.reports, 3u);
    EXPECT_EQ(c.bad_reports, 0u);
    EXPECT_EQ(c.transfer_errors, 0u);
    EXPECT_EQ(c.to_json().at("reports"), 3);
}

TEST_F(UsbInputTest, ReadsTheSixAxisSpaceMouseAndTwoGamepadsAtOnce) {
    auto& compact = bed_->add_device(test::spacemouse_compact());
    auto& pad = bed_->add_device(test::dual_action());
    auto& ds4 = bed_->add_device(test::dualshock4());
    UsbInput& in = start();
    ASSERT_TRUE(wait_open(3));
    auto keys = in.open_devices();
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(keys, (std::vector<std::string>{"usb 1-1 256f:c635", "usb 1-2 046d:c216", "usb 1-3 054c:05c4"}));
    EXPECT_EQ(hub_.connected_devices(), 3u);

    // The two at rest contribute 0, so the combination shows the one that moves.
    ASSERT_TRUE(send(pad, test::dual_action_report(128, 128, 128, 128)));
    ASSERT_TRUE(send(ds4, test::dualshock4_report(128, 128, 128, 128)));
    EXPECT_EQ(hub_.combined().axes, NavAxes{});

    ASSERT_TRUE(send(compact, test::spacemouse_report6(350, 70, -35, -350, 175, -175)));
    expect_axes(hub_.combined().axes, 1.0, 0.1, -0.2, -1.0, 0.5, 0.5);
    ASSERT_TRUE(send(compact, test::spacemouse_report6(0, 0, 0, 0, 0, 0)));

    ASSERT_TRUE(send(pad, test::dual_action_report(192, 64, 0, 255)));
    expect_axes(hub_.combined().axes, 64.0 / 127, 0, 64.0 / 127, -1.0, 1.0, 0);
    ASSERT_TRUE(send(pad, test::dual_action_report(128, 128, 128, 128)));

    ASSERT_TRUE(send(ds4, test::dualshock4_report(255, 128, 128, 1, 0, 255)));
    expect_axes(hub_.combined().axes, 1.0, 1.0, 0, 1.0, 0, 0);
    EXPECT_EQ(ds4.claims(), 1);
    EXPECT_EQ(in.counters().bad_reports, 0u);
}

TEST_F(UsbInputTest, HotplugEventPicksUpADevicePluggedInLaterAndUnplugStopsTheCamera) {
    UsbInputOptions opts;
    opts.rescan_interval = std::chrono::hours(1);  // only the hotplug event can find it
    UsbInput& in = start(opts);
    std::this_thread::sleep_for(50ms);
    EXPECT_TRUE(in.open_devices().empty());
    EXPECT_FALSE(hub_.combined().connected);

    auto& mouse = bed_->add_device(test::space_navigator());
    ASSERT_TRUE(wait_open(1, 2000ms)) << "no hotplug arrival";
    ASSERT_TRUE(send(mouse, test::spacemouse_report(1, 350, 0, 0)));
    EXPECT_NEAR(hub_.combined().axes.right, 1.0, kEps);

    // Pulled out while deflected: the hub forgets it at once, nothing keeps pushing the camera.
    const auto t0 = std::chrono::steady_clock::now();
    bed_->unplug(mouse);
    ASSERT_TRUE(test::wait_until([&] { return hub_.connected_devices() == 0; }));
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 1s);
    const NavSample s = hub_.combined();
    EXPECT_FALSE(s.connected);
    EXPECT_EQ(s.axes, NavAxes{});
    ASSERT_TRUE(wait_open(0));
    ASSERT_TRUE(test::wait_until([&] { return in.counters().devices_closed == 1; }));
    EXPECT_EQ(in.counters().devices_opened, 1u);
    EXPECT_EQ(in.counters().transfer_errors, 0u);

    // Plugged into the same port again: a new address, the same key, read again.
    auto spec = test::space_navigator();
    spec.port = 1;
    auto& again = bed_->add_device(spec);
    ASSERT_TRUE(wait_open(1, 2000ms));
    EXPECT_EQ(in.open_devices(), std::vector<std::string>{"usb 1-1 046d:c626"});
    EXPECT_NE(again.address(), mouse.address());
    ASSERT_TRUE(send(again, test::spacemouse_report(1, 0, 0, -350)));
    EXPECT_NEAR(hub_.combined().axes.up, 1.0, kEps);
    EXPECT_EQ(in.counters().devices_opened, 2u);
}

TEST_F(UsbInputTest, RescanPicksUpDevicesWhenHotplugCallbacksAreOff) {
    UsbInputOptions opts = fast();
    opts.hotplug = false;
    UsbInput& in = start(opts);
    auto& pad = bed_->add_device(test::dual_action());
    ASSERT_TRUE(wait_open(1, 1000ms)) << "not found within a few rescan intervals";
    ASSERT_TRUE(send(pad, test::dual_action_report(255, 128, 128, 128)));
    EXPECT_NEAR(hub_.combined().axes.right, 1.0, kEps);
    bed_->unplug(pad);  // the ended transfer alone tells UsbInput
    ASSERT_TRUE(test::wait_until([&] { return hub_.connected_devices() == 0 && in.counters().devices_closed == 1; }));
}

TEST_F(UsbInputTest, SysfsRescanOpensADeviceLibusbWasNeverToldAbout) {
    UsbInput& in = start();
    // No uevent: libusb's own list never learns of it, as on a host without a udev daemon.
    auto& mouse = bed_->add_device(test::space_navigator(), test::Announce::Silently);
    ASSERT_TRUE(wait_open(1, 1000ms)) << "the rescan of /sys did not open it";
    EXPECT_EQ(in.open_devices(), std::vector<std::string>{"usb 1-1 046d:c626"});
    EXPECT_EQ(count_containing(capture_->lines(), "found by the rescan"), 1u);
    EXPECT_EQ(mouse.claims(), 1);
    ASSERT_TRUE(send(mouse, test::spacemouse_report(2, 0, 0, -175)));
    EXPECT_NEAR(hub_.combined().axes.yaw_left, 0.5, kEps);
    bed_->unplug(mouse);
    ASSERT_TRUE(test::wait_until([&] { return hub_.connected_devices() == 0 && in.counters().devices_closed == 1; }));
    std::this_thread::sleep_for(250ms);  // gone from /sys too: not opened again
    EXPECT_EQ(in.counters().devices_opened, 1u);
}

TEST_F(UsbInputTest, AccessDeniedIsLoggedOnceAndRetriedWhenTheNodeChanges) {
    auto& mouse = bed_->add_device(test::space_navigator());
    bed_->set_node_mode(mouse, 0);
    {
        // Root ignores mode 000; the event thread (started here) does not.
        test::WithoutFileAccessOverride as_a_user;
        start();
    }
    ASSERT_TRUE(test::wait_until([&] { return input_->counters().access_denied == 1; }));
    std::this_thread::sleep_for(350ms);  // three more rescans: no retry, no second message
    const UsbInputCounters c = input_->counters();
    EXPECT_EQ(c.access_denied, 1u);
    EXPECT_EQ(c.devices_opened, 0u);
    EXPECT_TRUE(input_->open_devices().empty());
    EXPECT_FALSE(hub_.combined().connected);
    const auto lines = capture_->lines();
    ASSERT_EQ(count_containing(lines, "no permission"), 1u);
    const std::string msg = *std::find_if(
        lines.begin(), lines.end(), [](const std::string& l) { return l.find("no permission") != std::string::npos; });
    EXPECT_EQ(msg, usb_access_denied_message(model_for(0x046d, 0xc626), 1, mouse.address()));
    EXPECT_NE(msg.find(mouse.devnode()), std::string::npos);

    // udev applies the rule: the node changes, the next rescan opens the device.
    bed_->set_node_mode(mouse, 0660);
    ASSERT_TRUE(wait_open(1, 1000ms));
    EXPECT_EQ(input_->counters().access_denied, 1u);
    EXPECT_EQ(count_containing(capture_->lines(), "no permission"), 1u);
    ASSERT_TRUE(send(mouse, test::spacemouse_report(1, 175, 0, 0)));
    EXPECT_NEAR(hub_.combined().axes.right, 0.5, kEps);
}

TEST_F(UsbInputTest, ABusyDeviceIsLoggedOnceAndTriedAgainAtEveryRescan) {
    auto& pad = bed_->add_device(test::dual_action());
    pad.set_busy(true);  // another program holds the interface
    UsbInput& in = start();
    ASSERT_TRUE(test::wait_until([&] { return in.counters().open_failures == 1; }));
    std::this_thread::sleep_for(250ms);
    EXPECT_EQ(in.counters().open_failures, 1u);
    EXPECT_EQ(count_containing(capture_->lines(), "another program holds it"), 1u);
    EXPECT_TRUE(in.open_devices().empty());
    pad.set_busy(false);  // it lets go: the next rescan claims it
    ASSERT_TRUE(wait_open(1, 1000ms));
    EXPECT_EQ(in.counters().access_denied, 0u);
    ASSERT_TRUE(send(pad, test::dual_action_report(128, 0, 128, 128)));
    EXPECT_NEAR(hub_.combined().axes.forward, 1.0, kEps);
}

TEST_F(UsbInputTest, BadReportsAreCountedAndNotApplied) {
    auto& mouse = bed_->add_device(test::space_navigator());
    UsbInput& in = start();
    ASSERT_TRUE(wait_open(1));
    mouse.send_report({9, 1, 2, 3, 4, 5, 6});  // unknown report id
    mouse.send_report({1, 0x5e, 0x01});        // report 1 cut short
    ASSERT_TRUE(test::wait_until([&] { return in.counters().bad_reports == 2; }));
    EXPECT_EQ(hub_.combined().axes, NavAxes{});
    EXPECT_EQ(hub_.combined().reports, 0u);
    EXPECT_EQ(count_containing(capture_->lines(), "report rejected"), 1u);  // once per device
    ASSERT_TRUE(send(mouse, test::spacemouse_report(1, 175, 0, 0)));
    EXPECT_NEAR(hub_.combined().axes.right, 0.5, kEps);
    EXPECT_EQ(in.counters().reports, 3u);
}

TEST_F(UsbInputTest, StopReleasesTheInterfaceAndGivesTheKernelDriverBack) {
    auto& mouse = bed_->add_device(test::space_navigator());
    UsbInput& in = start();
    ASSERT_TRUE(wait_open(1));
    ASSERT_TRUE(send(mouse, test::spacemouse_report(1, 350, 0, 0)));
    const auto t0 = std::chrono::steady_clock::now();
    in.stop();
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 1s);
    EXPECT_EQ(mouse.releases(), 1);
    EXPECT_EQ(mouse.driver_reattaches(), 1);
    EXPECT_TRUE(mouse.kernel_driver_bound());
    EXPECT_EQ(mouse.urbs_in_flight(), 0);
    EXPECT_FALSE(hub_.combined().connected);
    EXPECT_TRUE(in.open_devices().empty());
    const UsbInputCounters c = in.counters();
    EXPECT_EQ(c.devices_opened, 1u);
    EXPECT_EQ(c.devices_closed, 1u);
    in.stop();  // idempotent
}

TEST_F(UsbInputTest, NoDevicesIsFine) {
    bed_->add_device({"a keyboard", 0x046d, 0xc31c});  // not in the table: left alone
    UsbInput& in = start();
    std::this_thread::sleep_for(250ms);
    EXPECT_TRUE(in.open_devices().empty());
    EXPECT_FALSE(hub_.combined().connected);
    const UsbInputCounters c = in.counters();
    EXPECT_EQ(c.devices_opened + c.access_denied + c.open_failures + c.reports, 0u);
    const auto t0 = std::chrono::steady_clock::now();
    in.stop();
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 500ms);
}

#pragma once
// Where a navigation device puts its axes and buttons in the HID input reports it sends on its
// interrupt-IN endpoint, and the parser that folds one report into a NavSample.
//
// A layout is a list of reports; each report is a list of fields. A field is a run of bits
// (little-endian, bit 0 = the least significant bit of byte 0, as HID numbers them) that either
//   - drives one NavAxes member: value = (raw - centre) / half_range * scale, summed over the
//     report's fields that drive the same axis and clamped to -1..1; or
//   - holds buttons: bit k of the field is button first_button + k.
// bit_offset counts from the first byte of the report as it arrives from the device, i.e. the
// report id byte is byte 0 when the layout uses report ids (as a USB capture shows the report).
//
// A report only updates what it carries: the old 3Dconnexion protocol sends translation in
// report 1 and rotation in report 2, so report 2 must not zero the translation. A field that
// lies (even partly) beyond the end of the received report is not carried by it; a report
// shorter than its min_bytes is rejected. This lets one layout read both 3D-mouse protocols:
// report 1 with 7 bytes (translation only) or 13 bytes (all six axes).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "nav_input.hpp"

namespace cupola {

// The six members of NavAxes, by name.
enum class NavAxis { Right, Up, Forward, PitchUp, YawLeft, RollCcw };

const char* nav_axis_name(NavAxis axis);                             // "right", "pitch_up", ...
std::optional<NavAxis> nav_axis_from_name(const std::string& name);  // nullopt for an unknown name
double& nav_axis(NavAxes& axes, NavAxis axis);

struct HidField {
    enum class Target { Axis, Buttons };
    Target target = Target::Axis;
    uint32_t bit_offset = 0;  // from bit 0 of byte 0 of the report (the id byte, when ids are used)
    uint32_t bit_size = 8;    // 1..32
    bool is_signed = false;   // two's complement

    // Target::Axis
    NavAxis axis = NavAxis::Right;
    double centre = 0.0;      // raw value at rest
    double half_range = 1.0;  // raw distance from centre to full deflection (non-zero)
    double scale = 1.0;       // sign and gain, e.g. -1 when the device's axis points the other way

    // Target::Buttons
    uint32_t first_button = 0;  // bit k -> NavSample::buttons bit first_button + k (< 32)

    size_t end_byte() const { return (bit_offset + bit_size + 7) / 8; }  // bytes needed to carry it
};

struct HidReport {
    uint8_t id = 0;                // byte 0 of the report when the layout uses report ids (ignored otherwise)
    size_t min_bytes = 1;          // shorter reports are rejected (the id byte included)
    std::vector<HidField> fields;  // none: a known report that carries nothing we use (ignored)
};

struct HidReportLayout {
    bool report_ids = true;  // false: the device sends one report without an id byte (reports[0])
    std::vector<HidReport> reports;
};

enum class ReportVerdict {
    Applied,    // the sample was updated with what the report carries
    Ignored,    // a known report without fields (e.g. a battery report)
    TooShort,   // shorter than the report's min_bytes (or empty): rejected, sample unchanged
    UnknownId,  // no report in the layout has this id: rejected, sample unchanged
};

const char* report_verdict_name(ReportVerdict v);

// Folds one received report into state.axes and state.buttons (nothing else is touched: the
// caller sets report_ns, reports, connected). Reads only data[0 .. len-1].
ReportVerdict apply_report(const HidReportLayout& layout, const uint8_t* data, size_t len, NavSample& state);

// The first problem with a layout ("" when it is usable): bit sizes, a zero half range, buttons
// past bit 31, duplicate report ids, no report, more than one report without ids.
std::string layout_problem(const HidReportLayout& layout);

}  // namespace cupola

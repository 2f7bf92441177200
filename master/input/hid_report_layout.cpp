#include "input/hid_report_layout.hpp"

#include <algorithm>
#include <array>
#include <set>

namespace cupola {

namespace {

constexpr std::array<const char*, 6> kAxisNames = {"right", "up", "forward", "pitch_up", "yaw_left", "roll_ccw"};

// The field's raw bits as an integer (sign-extended when signed). The caller has checked that
// the field lies inside data[0 .. len-1].
int64_t read_bits(const uint8_t* data, uint32_t bit_offset, uint32_t bit_size, bool is_signed) {
    uint64_t raw = 0;
    for (uint32_t i = 0; i < bit_size; ++i) {
        const uint32_t bit = bit_offset + i;
        if ((data[bit / 8] >> (bit % 8)) & 1u) raw |= uint64_t{1} << i;
    }
    if (is_signed && bit_size < 64 && ((raw >> (bit_size - 1)) & 1u)) raw |= ~uint64_t{0} << bit_size;
    return static_cast<int64_t>(raw);
}

const HidReport* find_report(const HidReportLayout& layout, const uint8_t* data) {
    if (!layout.report_ids) return layout.reports.empty() ? nullptr : &layout.reports.front();
    for (const auto& r : layout.reports)
        if (r.id == data[0]) return &r;
    return nullptr;
}

}  // namespace

const char* nav_axis_name(NavAxis axis) { return kAxisNames[static_cast<size_t>(axis)]; }

std::optional<NavAxis> nav_axis_from_name(const std::string& name) {
    for (size_t i = 0; i < kAxisNames.size(); ++i)
        if (name == kAxisNames[i]) return static_cast<NavAxis>(i);
    return std::nullopt;
}

double& nav_axis(NavAxes& axes, NavAxis axis) {
    switch (axis) {
        case NavAxis::Right:
            return axes.right;
        case NavAxis::Up:
            return axes.up;
        case NavAxis::Forward:
            return axes.forward;
        case NavAxis::PitchUp:
            return axes.pitch_up;
        case NavAxis::YawLeft:
            return axes.yaw_left;
        case NavAxis::RollCcw:
            break;
    }
    return axes.roll_ccw;
}

const char* report_verdict_name(ReportVerdict v) {
    switch (v) {
        case ReportVerdict::Applied:
            return "applied";
        case ReportVerdict::Ignored:
            return "ignored";
        case ReportVerdict::TooShort:
            return "too short";
        case ReportVerdict::UnknownId:
            break;
    }
    return "unknown report id";
}

ReportVerdict apply_report(const HidReportLayout& layout, const uint8_t* data, size_t len, NavSample& state) {
    if (data == nullptr || len == 0) return ReportVerdict::TooShort;
    const HidReport* report = find_report(layout, data);
    if (report == nullptr) return ReportVerdict::UnknownId;
    if (len < report->min_bytes) return ReportVerdict::TooShort;
    if (report->fields.empty()) return ReportVerdict::Ignored;

    // The axes this report carries start again from 0 and sum their fields; the others keep
    // their value from earlier reports.
    NavAxes axes = state.axes;
    std::set<NavAxis> carried;
    for (const auto& f : report->fields) {
        if (f.target != HidField::Target::Axis || f.end_byte() > len) continue;
        if (carried.insert(f.axis).second) nav_axis(axes, f.axis) = 0.0;
        const double raw = static_cast<double>(read_bits(data, f.bit_offset, f.bit_size, f.is_signed));
        nav_axis(axes, f.axis) += (raw - f.centre) / f.half_range * f.scale;
    }
    for (NavAxis a : carried) nav_axis(axes, a) = std::clamp(nav_axis(axes, a), -1.0, 1.0);

    uint32_t buttons = state.buttons;
    for (const auto& f : report->fields) {
        if (f.target != HidField::Target::Buttons || f.end_byte() > len) continue;
        const uint64_t bits = static_cast<uint64_t>(read_bits(data, f.bit_offset, f.bit_size, false));
        for (uint32_t k = 0; k < f.bit_size && f.first_button + k < 32; ++k) {
            const uint32_t mask = uint32_t{1} << (f.first_button + k);
            buttons = ((bits >> k) & 1u) ? (buttons | mask) : (buttons & ~mask);
        }
    }

    state.axes = axes;
    state.buttons = buttons;
    return ReportVerdict::Applied;
}

std::string layout_problem(const HidReportLayout& layout) {
    if (layout.reports.empty()) return "no reports";
    if (!layout.report_ids && layout.reports.size() != 1) return "a layout without report ids has exactly one report";
    std::set<int> ids;
    for (size_t r = 0; r < layout.reports.size(); ++r) {
        const auto& report = layout.reports[r];
        const std::string where = "reports[" + std::to_string(r) + "]";
        if (layout.report_ids && !ids.insert(report.id).second)
            return where + ": report id " + std::to_string(report.id) + " appears twice";
        if (report.min_bytes < 1) return where + ": min_bytes must be at least 1";
        for (size_t i = 0; i < report.fields.size(); ++i) {
            const auto& f = report.fields[i];
            const std::string fw = where + ".fields[" + std::to_string(i) + "]";
            if (f.bit_size < 1 || f.bit_size > 32) return fw + ": bits must be 1..32";
            if (f.target == HidField::Target::Axis && !(f.half_range != 0.0)) return fw + ": half_range must not be 0";
            if (f.target == HidField::Target::Buttons && f.first_button + f.bit_size > 32)
                return fw + ": buttons past button 31";
        }
    }
    return "";
}

}  // namespace cupola

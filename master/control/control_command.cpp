#include "control_command.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <vector>

#include "config/scene_config.hpp"
#include "overlay/overlay_kind.hpp"
#include "scene/night_sky.hpp"
#include "scene/sim_time.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

namespace {

double parse_number(const std::string& word, const std::string& what) {
    try {
        size_t used = 0;
        const double v = std::stod(word, &used);
        if (used != word.size() || !std::isfinite(v)) throw std::invalid_argument(word);
        return v;
    } catch (const std::exception&) {
        throw ControlError(what + ": \"" + word + "\" is not a number");
    }
}

void expect_count(const std::vector<std::string>& w, size_t lo, size_t hi, const std::string& usage) {
    if (w.size() < lo || w.size() > hi) throw ControlError("usage: " + usage);
}

}  // namespace

std::string lower_case(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

const std::string& control_help() {
    static const std::string text =
        "commands: goto <body> [seconds] [height <m>] | mode orbit|fly|walk [body] | time rate <x> | time set <UTC> | "
        "play [show.json] | pause | resume | stop | set shadow_mode <mode>|show | set exposure <x>|auto|show | "
        "set star_limit <mag>|show | set twinkle on|off|forced|show | set sky_brightness <mag>|show | "
        "set bortle <1-9>|show | show|hide <overlay> | show overlays show | pattern grid|white|black|off|show | "
        "head <x> <y> <z> [yaw pitch roll] | head release | status | quit | help";
    return text;
}

namespace {

using Words = std::vector<std::string>;

// The line's words, after the checks on its length and characters.
Words split_control_line(const std::string& line) {
    if (line.size() > 1024)
        throw ControlError("line too long (" + std::to_string(line.size()) + " bytes, at most 1024)");
    for (unsigned char c : line)
        if (c < 0x20 && c != '\t' && c != '\r')
            throw ControlError("control character " + std::to_string(c) + " in the line");
    std::istringstream in(line);
    Words w;
    for (std::string word; in >> word;) w.push_back(word);
    if (w.empty()) throw ControlError("empty line; " + control_help());
    return w;
}

// goto <body> [seconds] [height <m>]: the words after the body are the seconds, then "height" and
// the height above the ground to land at.
void parse_goto(const Words& w, ControlCommand& c) {
    const char* usage = "goto <body> [seconds] [height <m>]";
    expect_count(w, 2, 5, usage);
    c.verb = ControlVerb::Goto;
    c.body = w[1];
    size_t k = 2;
    if (k < w.size() && lower_case(w[k]) != "height") {
        c.seconds = parse_number(w[k], "goto seconds");
        if (*c.seconds < 0.0 || *c.seconds > 600.0) throw ControlError("goto seconds: must be 0..600, not " + w[k]);
        ++k;
    }
    if (k == w.size()) return;
    if (lower_case(w[k]) != "height" || k + 2 != w.size())
        throw ControlError(std::string("goto: \"") + w[k] +
                           "\" where \"height <m>\" or the end belongs; usage: " + usage);
    c.height_m = parse_number(w[k + 1], "goto height");
    if (*c.height_m < 2.0 || *c.height_m > 1e9)
        throw ControlError("goto height: must be 2 .. 1e9 m above the ground, not " + w[k + 1]);
}

void parse_mode(const Words& w, ControlCommand& c) {
    expect_count(w, 2, 3, "mode orbit|fly|walk [body]");
    c.verb = ControlVerb::Mode;
    c.nav_mode = lower_case(w[1]);
    if (c.nav_mode != "orbit" && c.nav_mode != "fly" && c.nav_mode != "walk")
        throw ControlError("mode: \"" + w[1] + "\" is not one of orbit, fly, walk");
    if (w.size() == 3) c.body = w[2];
}

void parse_time(const Words& w, ControlCommand& c) {
    if (w.size() < 2) throw ControlError("usage: time rate <x> | time set <UTC>");
    const std::string what = lower_case(w[1]);
    if (what == "rate") {
        expect_count(w, 3, 3, "time rate <x>");
        c.verb = ControlVerb::TimeRate;
        c.rate = parse_number(w[2], "time rate");
        if (std::abs(c.rate) > 1e10) throw ControlError("time rate: " + w[2] + " is beyond +-1e10");
    } else if (what == "set") {
        expect_count(w, 3, 3, "time set <ISO-8601 UTC, e.g. 2024-04-08T18:17:00Z>");
        c.verb = ControlVerb::TimeSet;
        c.utc = w[2];
        try {
            c.sim_time_s = utc_iso_to_j2000_seconds(w[2]);
        } catch (const std::exception& e) {
            throw ControlError(std::string("time set: ") + e.what());
        }
    } else {
        throw ControlError("time: \"" + w[1] + "\" is not rate or set");
    }
}

// "set sky_brightness <mag/arcsec^2>|show" or "set bortle <1..9>|show": both give c.number in
// mag/arcsec^2, the setting named sky_brightness.
void parse_sky_brightness(const Words& w, ControlCommand& c) {
    const bool bortle = c.setting == "bortle";
    c.setting = "sky_brightness";
    if (c.value == "show") return;
    const double x = parse_number(w[2], "set " + w[1]);
    if (bortle) {
        if (x != std::floor(x) || x < 1.0 || x > 9.0)
            throw ControlError("set bortle: must be a class 1..9, not " + w[2]);
        c.number = bortle_zenith_mag_arcsec2(static_cast<int>(x));
    } else {
        if (!(x >= 14.0) || x > 24.0) throw ControlError("set sky_brightness: must be 14..24 mag/arcsec2, not " + w[2]);
        c.number = x;
    }
}

void parse_set(const Words& w, ControlCommand& c) {
    expect_count(w, 3, 3, "set shadow_mode|exposure|star_limit|twinkle|sky_brightness|bortle <value>");
    c.verb = ControlVerb::Set;
    c.setting = lower_case(w[1]);
    c.value = lower_case(w[2]);
    if (c.setting == "shadow_mode") {
        if (c.value != "show") {
            const auto& n = shadow_mode_names();
            if (std::find(n.begin(), n.end(), c.value) == n.end())
                throw ControlError("set shadow_mode: \"" + w[2] +
                                   "\" is not one of exact, fast, lut, illustrative, off, show");
        }
    } else if (c.setting == "exposure") {
        if (c.value != "auto" && c.value != "show") {
            const double x = parse_number(w[2], "set exposure");
            if (!(x >= 1e-12) || x > 1e6) throw ControlError("set exposure: must be in [1e-12, 1e6], not " + w[2]);
            c.number = x;
        }
    } else if (c.setting == "star_limit") {
        if (c.value != "show") {
            const double x = parse_number(w[2], "set star_limit");
            if (x < -30.0 || x > 30.0) throw ControlError("set star_limit: must be -30..30, not " + w[2]);
            c.number = x;
        }
    } else if (c.setting == "twinkle") {
        const auto& n = twinkle_mode_names();
        if (c.value != "show" && std::find(n.begin(), n.end(), c.value) == n.end())
            throw ControlError("set twinkle: \"" + w[2] + "\" is not one of on, off, forced, show");
    } else if (c.setting == "sky_brightness" || c.setting == "bortle") {
        parse_sky_brightness(w, c);
    } else {
        throw ControlError("set: \"" + w[1] +
                           "\" is not shadow_mode, exposure, star_limit, twinkle, sky_brightness or bortle");
    }
}

void parse_pattern(const Words& w, ControlCommand& c) {
    expect_count(w, 2, 2, "pattern grid|white|black|off|show");
    c.verb = ControlVerb::Pattern;
    c.pattern = lower_case(w[1]);
    const auto& n = alignment_pattern_names();
    if (c.pattern != "show" && std::find(n.begin(), n.end(), c.pattern) == n.end())
        throw ControlError("pattern: \"" + w[1] + "\" is not one of grid, white, black, off, show");
}

// "show NAME..." / "hide NAME..." (the words after the verb are the overlay's name, as in
// "show grid equatorial"), or "show overlays show".
void parse_overlay(const Words& w, ControlCommand& c) {
    expect_count(w, 2, 4, w[0] + " <overlay>");
    c.verb = ControlVerb::Overlay;
    std::string name;
    for (size_t i = 1; i < w.size(); ++i) name += (i > 1 ? " " : "") + lower_case(w[i]);
    if (name == "overlays show") return;  // the show's overlays again
    c.overlay_shown = lower_case(w[0]) == "show";
    try {
        c.overlay = static_cast<size_t>(overlay_from_name(name));
    } catch (const std::invalid_argument& e) {
        throw ControlError(w[0] + ": " + e.what());
    }
}

// "head release", or "head X Y Z [YAW PITCH ROLL]": a room point in metres, angles in degrees.
void parse_head(const Words& w, ControlCommand& c) {
    c.verb = ControlVerb::Head;
    if (w.size() == 2 && lower_case(w[1]) == "release") return;
    if (w.size() != 4 && w.size() != 7)
        throw ControlError("head: give x y z in metres, optionally yaw pitch roll in degrees, or \"release\"");
    std::array<double, 6> v{};
    const char* names[] = {"head x", "head y", "head z", "head yaw", "head pitch", "head roll"};
    for (size_t i = 1; i < w.size(); ++i) {
        v[i - 1] = parse_number(w[i], names[i - 1]);
        const double limit = i <= 3 ? 1e4 : 360.0;
        if (std::abs(v[i - 1]) > limit)
            throw ControlError(std::string(names[i - 1]) + ": must be within +-" +
                               (i <= 3 ? "10000 m" : "360 degrees"));
    }
    c.head = v;
}

}  // namespace

ControlCommand parse_control_line(const std::string& line) {
    const Words w = split_control_line(line);
    ControlCommand c;
    const std::string verb = lower_case(w[0]);
    if (verb == "goto") {
        parse_goto(w, c);
    } else if (verb == "mode") {
        parse_mode(w, c);
    } else if (verb == "time") {
        parse_time(w, c);
    } else if (verb == "play") {
        expect_count(w, 1, 2, "play [show.json]");
        c.verb = ControlVerb::Play;
        if (w.size() == 2) c.show_file = w[1];
    } else if (verb == "pause" || verb == "resume" || verb == "stop" || verb == "status" || verb == "quit" ||
               verb == "help") {
        expect_count(w, 1, 1, verb);
        c.verb = verb == "pause"    ? ControlVerb::Pause
                 : verb == "resume" ? ControlVerb::Resume
                 : verb == "stop"   ? ControlVerb::Stop
                 : verb == "status" ? ControlVerb::Status
                 : verb == "quit"   ? ControlVerb::Quit
                                    : ControlVerb::Help;
    } else if (verb == "set") {
        parse_set(w, c);
    } else if (verb == "pattern") {
        parse_pattern(w, c);
    } else if (verb == "head") {
        parse_head(w, c);
    } else if (verb == "show" || verb == "hide") {
        parse_overlay(w, c);
    } else {
        throw ControlError("unknown command \"" + w[0] + "\"; " + control_help());
    }
    return c;
}

}  // namespace cupola

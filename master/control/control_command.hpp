#pragma once
// The master's control language: one command per line, from a local socket or standard input
// (control_server). Words are separated by spaces; body names and keywords are case-insensitive.
//
//   goto <body> [seconds]          fly to the body and orbit it (default duration: input.goto_seconds)
//   mode orbit|fly|walk [body]     navigation mode (orbit/walk: around/on the body, default the nearest)
//   time rate <x>                  simulation seconds per show second (negative: backwards)
//   time set <ISO-8601 UTC>        e.g. time set 2024-04-08T18:17:00Z
//   play [show.json]               resume the show, or load and start one (relative: to the cluster config)
//   pause | resume                 freeze / unfreeze the clock (a show's camera too)
//   stop                           leave the show; the camera stays where it is, under manual control
//   set shadow_mode <mode>         exact|fast|lut|illustrative|off, or "show" (the show's again)
//   set exposure <x>|auto|show     fixed exposure, the cluster's (auto) exposure, or the show's
//   set star_limit <mag>|show      faintest star drawn
//   set twinkle on|off|forced|show the stars' twinkling, or the show's (the scene's) again
//   set sky_brightness <mag>|show  the night sky's zenith brightness (V mag/arcsec^2), or the show's
//   set bortle <1..9>|show         the same as a Bortle class
//   pattern grid|white|black|off|show  alignment pattern on every channel instead of the scene
//                                  (docs/ALIGNMENT.md); "show": the show's pattern again
//   show|hide <overlay>            fade an overlay in or out ("show grid equatorial", "hide
//                                  constellations"; common/overlay/overlay_kind.hpp); "show
//                                  overlays show": every overlay as the show has it again
//   head <x> <y> <z> [yaw pitch roll]  the viewer's head at this room point (metres) and turned so
//                                  (degrees), whatever tracks it; "head release": the tracker's
//                                  (or the default eye) again
//   status                         one JSON line: frame, mode, time, rate, camera, show
//   quit                           stop the show and the cluster
//   help                           the list above
// Every command is answered with one line: "ok <what happened>" or "error <what was wrong>".
#include <array>
#include <optional>
#include <stdexcept>
#include <string>

namespace cupola {

// A line that is not a command: names the word that was wrong and why.
struct ControlError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

enum class ControlVerb {
    Goto,
    Mode,
    TimeRate,
    TimeSet,
    Play,
    Pause,
    Resume,
    Stop,
    Set,
    Pattern,
    Overlay,
    Head,
    Status,
    Quit,
    Help
};

struct ControlCommand {
    ControlVerb verb = ControlVerb::Help;
    std::string body;                           // goto, mode (optional): as typed
    std::optional<double> seconds;              // goto: flight duration
    std::optional<double> height_m;             // goto: land this high above the ground (relief or sphere)
    std::string nav_mode;                       // mode: orbit | fly | walk
    double rate = 1.0;                          // time rate
    double sim_time_s = 0.0;                    // time set: seconds since J2000 TT
    std::string utc;                            // time set: as typed
    std::string show_file;                      // play: as typed ("" = resume)
    std::optional<size_t> overlay;              // show / hide: the OverlayKind (none: every overlay)
    std::optional<bool> overlay_shown;          // show / hide; none: the show's again ("show overlays show")
    std::string setting;                        // set: shadow_mode | exposure | star_limit | twinkle | sky_brightness
    std::string value;                          // set: the value as typed (lower case)
    std::optional<double> number;               // set exposure / star_limit: the value when it is a number
    std::string pattern;                        // pattern: off | grid | white | black | show
    std::optional<std::array<double, 6>> head;  // head: x, y, z (m), yaw, pitch, roll (deg); none: release
};

// Parses one line (without its newline). Throws ControlError on anything else.
ControlCommand parse_control_line(const std::string& line);

// Lower case (ASCII), how words and body names are compared.
std::string lower_case(std::string s);

// The help text (one line per command, for "help").
const std::string& control_help();

}  // namespace cupola

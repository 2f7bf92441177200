#pragma once
// The master's simulation state between frames: who drives the camera and the clock.
//
//   Show mode   a show script plays: its keyframes give camera and time, its events the render
//               settings. pause freezes the show clock; play resumes it or starts another show.
//   Live mode   the presenter drives: the navigation model (3D mouse, gamepad, goto) moves the
//               camera, the simulation clock runs at `time rate` (show seconds per frame x rate).
//
// Device buttons run actions on press (input.buttons: next navigation mode, pause, play...).
// A manual command (goto, mode, time, stop) or a navigation device leaving its dead zone during
// a show (input.takeover) switches to Live mode from the show's current camera and time; the
// show's settings stay until changed. Clocks are rebased at each change so that, without any
// command or input, frame N shows exactly show time N x frame interval (make_frame_snapshot):
// a quiet master is as reproducible as before.
//
// Frames are stepped with the nominal frame interval (1 / frame_rate_hz, or the show's
// frame_interval_s), not wall time: every run of the same commands gives the same snapshots.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "control/control_command.hpp"
#include "input/nav_input.hpp"
#include "navigation/input_shaper.hpp"
#include "navigation/navigation_model.hpp"
#include "show_script.hpp"
#include "terrain/terrain_clearance.hpp"
#include "tracking/head_tracker.hpp"

namespace cupola {

// Show seconds per frame: 1 / frame_rate_hz, or the show's frame_interval_s when that is 0.
double show_frame_interval_s(const ClusterConfig& cluster, const ShowScript& show);

// One frame as the director defines it: the snapshot's simulation part (time, camera, bodies,
// shadow mode in settings.flags) and the settings the master applies when it finishes it.
struct DirectedFrame {
    Snapshot snapshot;
    ShowSettings settings;
    bool input_used = false;       // the navigation device moved the camera in this frame
    uint64_t input_report_ns = 0;  // when the newest device report used here arrived
};

class Director {
public:
    Director(const ClusterConfig& cluster, const SceneConfig& scene, ShowScript show);

    // The state for `frame` (frames increase; the first call may start anywhere, e.g. a resumed
    // show). `input` is the combined navigation devices' state at this moment.
    DirectedFrame frame(uint64_t frame, const NavSample& input);

    // Applies a command before `next_frame` (the first frame that shows its effect). Returns the
    // reply's text after "ok "; throws ControlError when it cannot be done (unknown body...).
    std::string apply(const ControlCommand& cmd, uint64_t next_frame);

    bool quit_requested() const { return quit_; }
    bool live() const { return live_; }
    double frame_interval_s() const { return dt_; }
    nlohmann::json status(uint64_t next_frame) const;
    // The viewer's head (VR walls and CAVEs): the tracker feeds it, "head" commands override it,
    // the master takes one pose from it per frame.
    HeadTracker& head() { return head_; }
    const HeadTracker& head() const { return head_; }

private:
    double show_time_at(uint64_t frame) const;
    double live_sim_time_at(uint64_t frame) const;
    double sim_time_at(uint64_t frame) const;
    void rebase(uint64_t frame);  // clocks keep their values at `frame`, new rules from there
    void take_over(uint64_t frame, const char* why);
    // The steps of apply() for the commands that take more than a line or two.
    std::string apply_goto(const ControlCommand& cmd, uint64_t next);
    // After a goto to body id, `height_m` above the ground: re-plans the flight to land that high
    // above the relief (or sphere) where it lands, at the landing frame's time.
    void land_above_ground(uint16_t id, double height_m, double seconds, uint64_t next,
                           const std::vector<NavBody>& bodies);
    std::string apply_mode(const ControlCommand& cmd, uint64_t next);
    std::string apply_play(const ControlCommand& cmd, uint64_t next);
    void apply_setting(const ControlCommand& cmd);  // "set": the overrides of the show
    std::string apply_pattern(const ControlCommand& cmd, uint64_t next);
    std::string apply_head(const ControlCommand& cmd, uint64_t next);
    AlignmentPattern pattern_at(uint64_t frame) const;  // the pattern frame() would give
    double show_rate_at(double show_time_s) const;
    void press_buttons(
        uint64_t frame,
        const NavSample& input);  // input.button_actions, on press  // simulation seconds per show second there
    uint16_t body_id(const std::string& name) const;            // throws ControlError
    std::vector<BodyState> states_at(double sim_time_s) const;  // every body, from the ephemeris

    const ClusterConfig& cluster_;
    const SceneConfig& scene_;
    terrain::TerrainClearance clearance_;  // the camera stays above the relief
    HeadTracker head_;
    ShowScript show_;
    double dt_;  // show seconds per frame
    bool live_ = false;
    bool paused_ = false;
    bool quit_ = false;
    // Show clock: show_time(frame) = show_base_ + (paused ? 0 : (frame - base_frame_) x dt)
    double show_base_ = 0.0;
    // Live clock: sim_time(frame) = sim_base_ + (paused ? 0 : (frame - base_frame_) x dt x rate_)
    double sim_base_ = 0.0;
    double rate_ = 1.0;
    uint64_t base_frame_ = 0;
    std::optional<uint64_t> last_frame_;  // the last frame produced
    uint64_t last_reports_ = 0;           // the devices' report count at the last frame
    uint32_t last_buttons_ = 0;           // buttons held at the last frame (actions fire on press)
    ShowSettings live_settings_;          // Live mode: the show's settings when it stopped
    // set commands, over the show's or live settings (none: not overridden)
    std::optional<ShadowMode> shadow_override_;
    std::optional<std::optional<float>> exposure_override_;  // inner none: the cluster's exposure
    std::optional<float> star_limit_override_;
    std::optional<double> sky_brightness_override_;
    std::array<std::optional<bool>, kOverlayCount>
        overlay_override_;  // "show" / "hide" (none: the show's)  // "set sky_brightness" / "set bortle" (mag/arcsec^2)
    std::optional<TwinkleMode> twinkle_override_;       // "set twinkle": over the show's (none: the show's)
    std::optional<AlignmentPattern> pattern_override_;  // "pattern": over the show's (none: the show's)
    InputShaper shaper_;
    NavigationModel nav_;
};

}  // namespace cupola

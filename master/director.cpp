#include "director.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "config/config_error.hpp"
#include "eclipse/shadow_casters.hpp"
#include "navigation/nav_body.hpp"
#include "scene/ephemeris.hpp"
#include "scene/sim_time.hpp"

namespace cupola {

namespace {

NavigationTuning navigation_tuning(const InputConfig& in) {
    NavigationTuning t;
    t.speed_per_altitude = in.speed_per_altitude;
    t.min_speed_m_s = in.min_speed_m_s;
    t.turn_rate_deg_s = in.turn_rate_deg_s;
    t.orbit_rate_deg_s = in.orbit_rate_deg_s;
    return t;
}

ShaperTuning shaper_tuning(const InputConfig& in) {
    ShaperTuning t;
    t.dead_zone = in.dead_zone;
    t.smoothing_s = in.smoothing_s;
    return t;
}

bool any_motion(const NavAxes& a) {
    return a.right != 0.0 || a.up != 0.0 || a.forward != 0.0 || a.pitch_up != 0.0 || a.yaw_left != 0.0 ||
           a.roll_ccw != 0.0;
}

// UTC of a simulation time, or a note where ERFA's calendar ends (a clock run far away).
std::string utc_or_note(double t) {
    try {
        return tt_to_utc_iso(t);
    } catch (const std::exception&) {
        return "(outside the calendar)";
    }
}

}  // namespace

double show_frame_interval_s(const ClusterConfig& cluster, const ShowScript& show) {
    return cluster.frame_rate_hz > 0 ? 1.0 / cluster.frame_rate_hz : show.frame_interval_s();
}

Director::Director(const ClusterConfig& cluster, const SceneConfig& scene, ShowScript show)
    : cluster_(cluster),
      scene_(scene),
      clearance_(scene),
      head_(cluster.room.tracking, cluster.room.eye_m),
      show_(std::move(show)),
      dt_(show_frame_interval_s(cluster, show_)),
      shaper_(shaper_tuning(cluster.input)),
      nav_(navigation_tuning(cluster.input)) {}

double Director::show_time_at(uint64_t frame) const {
    if (paused_ || live_) return show_base_;  // live: where the show was left
    return show_base_ + static_cast<double>(static_cast<int64_t>(frame - base_frame_)) * dt_;
}

double Director::live_sim_time_at(uint64_t frame) const {
    if (paused_) return sim_base_;
    return sim_base_ + static_cast<double>(static_cast<int64_t>(frame - base_frame_)) * dt_ * rate_;
}

double Director::sim_time_at(uint64_t frame) const {
    return live_ ? live_sim_time_at(frame) : show_.evaluate(show_time_at(frame), scene_).sim_time_s;
}

double Director::show_rate_at(double show_time_s) const {
    const double h = std::max(dt_, 1e-3);
    return (show_.evaluate(show_time_s + h, scene_).sim_time_s - show_.evaluate(show_time_s, scene_).sim_time_s) / h;
}

void Director::rebase(uint64_t frame) {
    show_base_ = show_time_at(frame);  // unchanged while live
    sim_base_ = live_sim_time_at(frame);
    base_frame_ = frame;
}

void Director::take_over(uint64_t frame, const char* why) {
    if (live_) return;
    const double t_show = show_time_at(frame);
    const Snapshot s = show_.evaluate(t_show, scene_);
    show_base_ = t_show;  // where "play" resumes
    sim_base_ = s.sim_time_s;
    rate_ = show_rate_at(t_show);  // paused or not: resume runs at the show's rate
    base_frame_ = frame;
    live_settings_ = show_.settings_at(t_show);
    const std::vector<NavBody> bodies = nav_bodies(scene_, s.bodies);
    nav_.set_pose({s.camera_position_m, s.camera_orientation}, bodies);
    // A ground observer keeps standing on the ground (and turning with the planet).
    const auto& keys = show_.keyframes();
    size_t i = 0;
    while (i + 1 < keys.size() && keys[i + 1].at_s <= t_show) ++i;
    if (keys[i].camera.observer && keys[i].camera.anchor)
        nav_.set_mode(NavMode::SurfaceWalk, bodies, *keys[i].camera.anchor);
    shaper_.reset();
    live_ = true;
    spdlog::info("director: {} takes over from the show at show time {:.3f} s (frame {}); clock rate {:g}", why, t_show,
                 frame, rate_);
}

std::vector<BodyState> Director::states_at(double sim_time_s) const {
    std::vector<BodyState> out;
    for (const auto& b : scene_.bodies) out.push_back(body_state(b, sim_time_s));
    return out;
}

uint16_t Director::body_id(const std::string& name) const {
    for (const auto& b : scene_.bodies)
        if (lower_case(b.name) == lower_case(name)) return b.id;
    std::string names;
    for (const auto& b : scene_.bodies) names += (names.empty() ? "" : ", ") + b.name;
    throw ControlError("no body named \"" + name + "\" in the scene (bodies: " + names + ")");
}

void Director::press_buttons(uint64_t frame, const NavSample& input) {
    const uint32_t held = input.connected ? input.buttons : 0u;
    const uint32_t pressed = held & ~last_buttons_;
    last_buttons_ = held;
    for (int b = 0; b < 32; ++b) {
        if (!(pressed & (1u << b))) continue;
        const auto it = cluster_.input.button_actions.find(b);
        if (it == cluster_.input.button_actions.end() || it->second == "none") continue;
        const std::string& action = it->second;
        ControlCommand c;
        if (action == "next_mode") {
            c.verb = ControlVerb::Mode;
            const NavMode now = live_ ? nav_.mode() : NavMode::SurfaceWalk;  // from a show: orbit first
            c.nav_mode = now == NavMode::Orbit ? "fly" : now == NavMode::FreeFly ? "walk" : "orbit";
        } else if (action == "toggle_pause") {
            c.verb = paused_ ? ControlVerb::Resume : ControlVerb::Pause;
        } else if (action == "play") {
            c.verb = ControlVerb::Play;
        } else if (action == "stop") {
            c.verb = ControlVerb::Stop;
        } else {  // orbit_nearest
            c.verb = ControlVerb::Mode;
            c.nav_mode = "orbit";
        }
        try {
            spdlog::info("director: button {} ({}): {}", b, action, apply(c, frame));
        } catch (const std::exception& e) {
            spdlog::warn("director: button {} ({}): {}", b, action, e.what());
        }
    }
}

DirectedFrame Director::frame(uint64_t frame, const NavSample& input) {
    press_buttons(frame, input);
    const double step_dt = last_frame_ && frame > *last_frame_ ? static_cast<double>(frame - *last_frame_) * dt_ : 0.0;
    const NavAxes axes = shaper_.shape(input, step_dt > 0.0 ? step_dt : dt_);
    const bool moved = any_motion(axes);
    // Only a device held outside its dead zone now takes over (not a smoothing tail).
    const bool held = shaper_.outside_dead_zone(input);
    if (!live_ && held && moved && cluster_.input.takeover) take_over(frame, "the navigation device");

    DirectedFrame out;
    if (!live_) {
        const double t_show = show_time_at(frame);
        out.snapshot = show_.evaluate(t_show, scene_);
        out.settings = show_.settings_at(t_show);
    } else {
        Snapshot& s = out.snapshot;
        s.sim_time_s = live_sim_time_at(frame);
        s.bodies = states_at(s.sim_time_s);
        const CameraPose pose = nav_.step(moved ? axes : NavAxes{}, step_dt, nav_bodies(scene_, s.bodies));
        s.camera_position_m = pose.position_m;
        // Walking, the eye keeps its height above the relief, not above the sphere.
        for (const BodyState& b : s.bodies)
            if (nav_.mode() == NavMode::SurfaceWalk && b.id == nav_.anchor())
                s.camera_position_m = clearance_.on_relief(b, s.camera_position_m);
        s.camera_orientation = pose.orientation;
        out.settings = live_settings_;
        out.input_used = moved;
    }
    // Whatever moved it, the camera stays above the relief (terrain/terrain_clearance.hpp).
    if (clearance_.any())
        out.snapshot.camera_position_m = clearance_.keep_above(out.snapshot.bodies, out.snapshot.camera_position_m);
    // A fresh report (not one already counted) dates the input of this frame.
    if (input.reports != last_reports_) out.input_report_ns = input.report_ns;
    last_reports_ = input.reports;
    if (shadow_override_) out.settings.shadow_mode = shadow_override_;
    if (exposure_override_) out.settings.exposure = *exposure_override_;
    if (star_limit_override_) out.settings.star_magnitude_limit = star_limit_override_;
    if (pattern_override_) out.settings.pattern = pattern_override_;
    if (twinkle_override_) out.settings.twinkle = twinkle_override_;
    if (sky_brightness_override_) out.settings.sky_brightness = sky_brightness_override_;
    for (size_t k = 0; k < kOverlayCount; ++k)
        if (overlay_override_[k]) out.settings.overlays[k] = overlay_override_[k];
    uint32_t& flags = out.snapshot.settings.flags;
    flags = with_shadow_mode(flags, out.settings.shadow_mode.value_or(scene_.shadows.mode));
    flags = with_alignment_pattern(flags, out.settings.pattern.value_or(AlignmentPattern::Off));
    flags = with_twinkle_mode(flags, out.settings.twinkle.value_or(scene_.stars.twinkle));
    last_frame_ = frame;
    return out;
}

std::string Director::apply(const ControlCommand& cmd, uint64_t next) {
    char buf[256];
    switch (cmd.verb) {
        case ControlVerb::Goto:
            return apply_goto(cmd, next);
        case ControlVerb::Mode:
            return apply_mode(cmd, next);
        case ControlVerb::TimeRate:
            take_over(next, "time rate");
            rebase(next);
            rate_ = cmd.rate;
            std::snprintf(buf, sizeof buf, "time rate %g from frame %llu", rate_,
                          static_cast<unsigned long long>(next));
            return buf;
        case ControlVerb::TimeSet:
            take_over(next, "time set");
            rebase(next);
            sim_base_ = cmd.sim_time_s;
            return "time " + utc_or_note(sim_base_) + " at frame " + std::to_string(next);
        case ControlVerb::Play:
            return apply_play(cmd, next);
        case ControlVerb::Pause:
            rebase(next);
            paused_ = true;
            return "paused at frame " + std::to_string(next);
        case ControlVerb::Resume:
            rebase(next);
            paused_ = false;
            return "running from frame " + std::to_string(next);
        case ControlVerb::Stop:
            if (!live_) take_over(next, "stop");
            return "manual control from frame " + std::to_string(next);
        case ControlVerb::Set:
            apply_setting(cmd);
            return cmd.setting + " " + cmd.value + " from frame " + std::to_string(next);
        case ControlVerb::Pattern:
            return apply_pattern(cmd, next);
        case ControlVerb::Overlay:
            if (!cmd.overlay) {
                overlay_override_ = {};
                return "overlays as the show has them from frame " + std::to_string(next);
            }
            overlay_override_[*cmd.overlay] = cmd.overlay_shown;
            return std::string(*cmd.overlay_shown ? "showing " : "hiding ") + overlay_names()[*cmd.overlay] +
                   " from frame " + std::to_string(next);
        case ControlVerb::Head:
            return apply_head(cmd, next);
        case ControlVerb::Status:
            return status(next).dump();
        case ControlVerb::Quit:
            quit_ = true;
            return "quit before frame " + std::to_string(next);
        case ControlVerb::Help:
            return control_help();
    }
    return "";
}

std::string Director::apply_head(const ControlCommand& cmd, uint64_t next) {
    if (!cmd.head) {
        head_.set_control_pose(std::nullopt);
        return "head released to the tracker (or the default eye) from frame " + std::to_string(next);
    }
    const std::array<double, 6>& h = *cmd.head;
    HeadPose p;
    p.position_m = glm::dvec3(h[0], h[1], h[2]);
    p.orientation = glm::normalize(glm::quat_cast(channel_rotation(EulerDeg{h[3], h[4], h[5]})));
    head_.set_control_pose(p);
    char buf[160];
    std::snprintf(buf, sizeof buf, "head at (%g, %g, %g) m, yaw %g pitch %g roll %g deg from frame %llu", h[0], h[1],
                  h[2], h[3], h[4], h[5], static_cast<unsigned long long>(next));
    return buf;
}

std::string Director::apply_goto(const ControlCommand& cmd, uint64_t next) {
    const uint16_t id = body_id(cmd.body);
    take_over(next, "goto");
    const double secs = cmd.seconds.value_or(cluster_.input.goto_seconds);
    const std::vector<NavBody> bodies = nav_bodies(scene_, states_at(live_sim_time_at(next)));
    nav_.fly_to(id, secs, bodies);
    if (cmd.height_m) land_above_ground(id, *cmd.height_m, secs, next, bodies);
    char buf[256];
    std::snprintf(buf, sizeof buf, "goto %s: flying for %.3g s from frame %llu", scene_.bodies[id].name.c_str(), secs,
                  static_cast<unsigned long long>(next));
    return buf;
}

void Director::land_above_ground(uint16_t id, double height_m, double seconds, uint64_t next,
                                 const std::vector<NavBody>& bodies) {
    // The frames step by dt_ (the flight too), so the landing frame and its sim time are known.
    const uint64_t landing = next + static_cast<uint64_t>(std::llround(seconds / dt_));
    const std::vector<BodyState> at_landing = states_at(live_sim_time_at(landing));  // paused: no change
    const BodyState* body = nullptr;
    for (const BodyState& b : at_landing)
        if (b.id == id) body = &b;
    if (!body) return;
    const double r = scene_.bodies[id].radius_m;
    const glm::dvec3 under = body->position_m + nav_.landing_direction() * r;
    const double ground_m = clearance_.ground_height_m(*body, under);
    // Never lower than the clearance the master keeps above the relief (the parser asks for that much).
    nav_.fly_to(id, seconds, bodies, (r + ground_m + height_m) / r, r + ground_m + terrain::kGroundClearance_m);
}

std::string Director::apply_mode(const ControlCommand& cmd, uint64_t next) {
    const NavMode m = cmd.nav_mode == "orbit"  ? NavMode::Orbit
                      : cmd.nav_mode == "walk" ? NavMode::SurfaceWalk
                                               : NavMode::FreeFly;
    std::optional<uint16_t> target;
    if (!cmd.body.empty()) target = body_id(cmd.body);
    take_over(next, "mode");
    nav_.set_mode(m, nav_bodies(scene_, states_at(live_sim_time_at(next))), target);
    return "mode " + std::string(nav_mode_name(nav_.mode())) + " around " + scene_.bodies[nav_.anchor()].name +
           " from frame " + std::to_string(next);
}

std::string Director::apply_play(const ControlCommand& cmd, uint64_t next) {
    if (!cmd.show_file.empty()) {
        const std::string path = resolve_path(cluster_.directory, cmd.show_file);
        try {
            show_ = ShowScript::load(path, scene_);
        } catch (const std::exception& e) {
            throw ControlError(std::string("play: ") + e.what());
        }
        show_base_ = 0.0;
    } else if (!live_ && !paused_) {
        return "already playing " + show_.file();
    } else if (live_) {
        // show_base_ still holds the show time where the show was left.
    }
    dt_ = show_frame_interval_s(cluster_, show_);
    live_ = false;
    paused_ = false;
    base_frame_ = next;
    shaper_.reset();  // a device's smoothing tail must not take the show over again
    char buf[256];
    std::snprintf(buf, sizeof buf, "playing %s from show time %.3f s at frame %llu", show_.file().c_str(), show_base_,
                  static_cast<unsigned long long>(next));
    return buf;
}

void Director::apply_setting(const ControlCommand& cmd) {
    if (cmd.setting == "shadow_mode") {
        if (cmd.value == "show")
            shadow_override_.reset();
        else
            shadow_override_ = shadow_mode_from_name(cmd.value);
    } else if (cmd.setting == "exposure") {
        if (cmd.value == "show")
            exposure_override_.reset();
        else if (cmd.value == "auto")
            exposure_override_ = std::optional<float>{};
        else
            exposure_override_ = std::optional<float>(static_cast<float>(cmd.number.value()));
    } else if (cmd.setting == "twinkle") {
        if (cmd.value == "show")
            twinkle_override_.reset();
        else
            twinkle_override_ = twinkle_mode_from_name(cmd.value);
    } else if (cmd.setting == "sky_brightness") {
        if (cmd.value == "show")
            sky_brightness_override_.reset();
        else
            sky_brightness_override_ = cmd.number.value();
    } else {
        if (cmd.value == "show")
            star_limit_override_.reset();
        else
            star_limit_override_ = static_cast<float>(cmd.number.value());
    }
}

AlignmentPattern Director::pattern_at(uint64_t frame) const {
    if (pattern_override_) return *pattern_override_;
    const ShowSettings shown = live_ ? live_settings_ : show_.settings_at(show_time_at(frame));
    return shown.pattern.value_or(AlignmentPattern::Off);
}

std::string Director::apply_pattern(const ControlCommand& cmd, uint64_t next) {
    if (cmd.pattern == "show") {
        pattern_override_.reset();
        return std::string("pattern show (") + alignment_pattern_name(pattern_at(next)) + " now) from frame " +
               std::to_string(next);
    }
    try {
        pattern_override_ = alignment_pattern_from_name(cmd.pattern);
    } catch (const std::invalid_argument& e) {
        throw ControlError(std::string("pattern: ") + e.what());
    }
    return "pattern " + cmd.pattern + " from frame " + std::to_string(next);
}

nlohmann::json Director::status(uint64_t next) const {
    const double t = sim_time_at(next);
    nlohmann::json j{{"frame", next},
                     {"mode", live_ ? "live" : "show"},
                     {"paused", paused_},
                     {"show", show_.file()},
                     {"show_time_s", show_time_at(next)},
                     {"sim_time_s", t},
                     {"utc", utc_or_note(t)},
                     {"rate", paused_ ? 0.0
                              : live_ ? rate_
                                      : show_rate_at(show_time_at(next))},
                     {"pattern", alignment_pattern_name(pattern_at(next))}};
    if (live_) {
        const auto bodies = nav_bodies(scene_, states_at(t));
        j["navigation"] = {{"mode", nav_mode_name(nav_.mode())},
                           {"anchor", scene_.bodies[nav_.anchor()].name},
                           {"altitude_m", nav_.altitude_m(bodies)},
                           {"flying", nav_.flying()}};
    }
    return j;
}

}  // namespace cupola

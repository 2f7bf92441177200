#pragma once
// A show: keyframes of simulation time and camera, interpolated per frame. Read from a JSON show
// file; every mistake throws ConfigError naming the file and the field.
//
// {
//   "frame_interval_s": 0.0333,            // show seconds per frame when frame_rate_hz is 0
//   "keyframes": [
//     { "at_s": 0,                          // show time of this keyframe (strictly increasing)
//       "time_utc": "2024-04-08T18:00:00Z", // simulation time here
//       "camera": { "anchor": "earth",      // body the camera rides with ("" or absent: world origin)
//                   "offset_m": [x, y, z],  // from the anchor, world (equatorial) axes, metres
//                   "look_at": "moon",      // or "look_direction": [x, y, z]
//                   "up": [0, 0, 1],        // world up hint (default: celestial north)
//                   "target_elevation_deg": 40 },  // raise the target above the dome's front horizon
//     "shadow_mode": "exact",               // optional: exact|fast|lut|illustrative|off from here on
//     "easing": "ease_in_out",              // camera, this key -> the next (default ease_in_out)
//     "time_easing": "linear" }             // simulation time, this key -> the next (default linear)
//   ],                                      // easings: linear|ease_in|ease_out|ease_in_out|hold
//   "events": [                             // optional: render settings switched at a show time
//     { "at_s": 12.5, "shadow_mode": "illustrative", "exposure": 2.0, "star_magnitude_limit": 5.5 },
//     { "at_s": 20, "exposure": "auto" }    // back to the cluster's exposure (auto or fixed)
//   ]
// }
// A ground observer instead of offset_m: "observer": { "lat_deg": 23.15, "lon_deg": 16.73,
// "alt_m": 2 } on the anchor body (geodetic WGS84 latitude on the Earth, rotating with it),
// looking along "look_azimuth_deg" (from north through east, default 180) and
// "look_elevation_deg" (default 0), or at "look_at"; the camera's up (the dome's apex) is the
// local zenith.
#include <optional>
#include <string>
#include <vector>

#include "config/scene_config.hpp"
#include "easing.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

struct ObserverSite {
    double lat_deg = 0.0;
    double lon_deg = 0.0;  // east positive
    double alt_m = 0.0;
    double look_azimuth_deg = 180.0;
    double look_elevation_deg = 0.0;
};

struct CameraKey {
    std::optional<uint16_t> anchor;  // body id
    glm::dvec3 offset_m{0.0};
    std::optional<ObserverSite> observer;  // on the anchor's surface (replaces offset_m)
    std::optional<uint16_t> look_at;       // body id
    glm::dvec3 look_direction{0, 1, 0};
    glm::dvec3 up{0, 0, 1};
    double target_elevation_deg = 0.0;
};

struct ShowKeyframe {
    double at_s = 0.0;
    double sim_time_s = 0.0;
    CameraKey camera;
    std::optional<ShadowMode> shadow_mode;     // from this keyframe on
    Easing camera_easing = Easing::EaseInOut;  // this key -> the next
    Easing time_easing = Easing::Linear;
};

// A change of render settings at a show time; unset fields keep their value.
struct ShowEvent {
    double at_s = 0.0;
    std::optional<ShadowMode> shadow_mode;
    std::optional<float> exposure;  // fixed exposure from here on
    bool exposure_auto = false;     // back to the cluster's own exposure
    std::optional<float> star_magnitude_limit;
};

// The render settings a show asks for at a show time (events and keyframes up to then).
struct ShowSettings {
    std::optional<ShadowMode> shadow_mode;      // none: the scene's default
    std::optional<float> exposure;              // none: the cluster's (auto) exposure
    std::optional<float> star_magnitude_limit;  // none: the scene's limit
};

class ShowScript {
public:
    ShowScript(std::vector<ShowKeyframe> keys, double frame_interval_s, std::vector<ShowEvent> events = {});
    static ShowScript load(const std::string& file, const SceneConfig& scene);

    // The snapshot for a show time: sim time, camera, every body's state (ephemeris) and the
    // shadow mode (the scene's default until a keyframe switches it) in settings.flags.
    Snapshot evaluate(double show_time_s, const SceneConfig& scene) const;
    // The settings in force at a show time (evaluate() applies the shadow mode to settings.flags;
    // the master applies exposure and star limit when it finishes the snapshot).
    ShowSettings settings_at(double show_time_s) const;
    // Show time of the last keyframe or event: where a played show "ends" (it keeps running).
    double duration_s() const;

    double frame_interval_s() const { return frame_interval_s_; }
    const std::vector<ShowKeyframe>& keyframes() const { return keys_; }
    const std::vector<ShowEvent>& events() const { return events_; }
    const std::string& file() const { return file_; }

private:
    std::vector<ShowKeyframe> keys_;
    std::vector<ShowEvent> events_;
    std::string file_;
    double frame_interval_s_;
};

}  // namespace cupola

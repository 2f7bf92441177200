#pragma once
// A show: keyframes of simulation time and camera, interpolated per frame. Read from a JSON show
// file; every mistake throws ConfigError naming the file and the field.
//
// The file format, each field's default, range and meaning: configs/schema/show.schema.json
// (docs/CONFIG.md is written from it; configs/shows/ has examples). In short: keyframes[] of
// at_s, time_utc and a camera (anchor body, offset_m or a ground observer, look_at or
// look_direction), with easings to the next key; events[] switch shadow mode, exposure, star
// magnitude limit and the alignment pattern (docs/ALIGNMENT.md) at a show time.
#include <array>
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
    std::optional<AlignmentPattern> pattern;                  // the alignment pattern from here on (Off: the scene)
    std::optional<TwinkleMode> twinkle;                       // the stars' twinkling from here on
    std::optional<double> sky_brightness;                     // the night sky's zenith brightness, V mag/arcsec^2
    std::array<std::optional<bool>, kOverlayCount> overlays;  // "show" / "hide": fade in or out
};

// The render settings a show asks for at a show time (events and keyframes up to then).
struct ShowSettings {
    std::optional<ShadowMode> shadow_mode;                    // none: the scene's default
    std::optional<float> exposure;                            // none: the cluster's (auto) exposure
    std::optional<float> star_magnitude_limit;                // none: the scene's limit
    std::optional<AlignmentPattern> pattern;                  // none: no pattern (the scene)
    std::optional<TwinkleMode> twinkle;                       // none: the scene's stars.twinkle
    std::optional<double> sky_brightness;                     // V mag/arcsec^2; none: the scene's stars.sky_brightness
    std::array<std::optional<bool>, kOverlayCount> overlays;  // shown or hidden; none: the scene's
};

class ShowScript {
public:
    ShowScript(std::vector<ShowKeyframe> keys, double frame_interval_s, std::vector<ShowEvent> events = {});
    static ShowScript load(const std::string& file, const SceneConfig& scene);

    // The snapshot for a show time: sim time, camera, every body's state (ephemeris), the shadow
    // mode (the scene's default until a keyframe switches it) and the alignment pattern in
    // settings.flags.
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

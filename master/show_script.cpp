#include "show_script.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <erfa.h>
#include <erfam.h>

#include "config/config_schema.hpp"
#include "config/json_reader.hpp"
#include "eclipse/shadow_casters.hpp"
#include "scene/ephemeris.hpp"
#include "scene/night_sky.hpp"
#include "scene/sim_time.hpp"

namespace cupola {

ShowScript::ShowScript(std::vector<ShowKeyframe> keys, double frame_interval_s, std::vector<ShowEvent> events)
    : keys_(std::move(keys)), events_(std::move(events)), frame_interval_s_(frame_interval_s) {
    if (keys_.empty()) throw std::invalid_argument("a show needs at least one keyframe");
    std::stable_sort(events_.begin(), events_.end(),
                     [](const ShowEvent& a, const ShowEvent& b) { return a.at_s < b.at_s; });
}

namespace {

// Defaults and ranges of every field: configs/schema/show.schema.json (JsonReader::declared_*).
// What a schema cannot say is checked here: body names of the scene, strictly increasing
// keyframe times, the UTC time itself, an observer only with an anchor and without offset_m,
// look_at or look_direction (not both, not zero), and a non-zero up.

std::optional<uint16_t> body_id(const JsonReader& c, const std::string& key, const SceneConfig& scene) {
    if (!c.has(key)) return std::nullopt;
    std::string name = c.string(key);
    if (name.empty()) return std::nullopt;
    const BodyConfig* b = scene.find(name);
    if (!b) c.fail(key, "no body named \"" + name + "\" in the scene " + scene.file);
    return b->id;
}

std::optional<ShadowMode> optional_shadow_mode(const JsonReader& r) {
    if (!r.has("shadow_mode")) return std::nullopt;
    return shadow_mode_from_name(r.one_of("shadow_mode", r.declared_choices("shadow_mode")));
}

ObserverSite read_observer(const JsonReader& o, const JsonReader& camera) {
    ObserverSite site;
    site.lat_deg = o.declared_number("lat_deg");
    site.lon_deg = o.declared_number("lon_deg");
    site.alt_m = o.declared_number("alt_m");
    o.reject_unknown_keys();
    site.look_azimuth_deg = camera.declared_number("look_azimuth_deg");
    site.look_elevation_deg = camera.declared_number("look_elevation_deg");
    return site;
}

CameraKey read_camera(const JsonReader& c, const SceneConfig& scene) {
    CameraKey k;
    k.anchor = body_id(c, "anchor", scene);
    k.offset_m = c.optional_dvec3("offset_m").value_or(glm::dvec3(0.0));
    if (auto o = c.optional_child("observer")) {
        if (!k.anchor) c.fail("observer", "an observer needs an anchor body to stand on");
        if (c.has("offset_m")) c.fail("offset_m", "give observer or offset_m, not both");
        k.observer = read_observer(*o, c);
    }
    k.look_at = body_id(c, "look_at", scene);
    if (auto d = c.optional_dvec3("look_direction")) {
        if (k.look_at) c.fail("look_direction", "give look_at or look_direction, not both");
        if (glm::length(*d) == 0.0) c.fail("look_direction", "must not be the zero vector");
        k.look_direction = glm::normalize(*d);
    } else if (!k.look_at && !k.observer) {
        c.fail("look_at", "missing: give look_at (a body) or look_direction");
    }
    if (auto u = c.optional_dvec3("up")) {
        if (glm::length(*u) == 0.0) c.fail("up", "must not be the zero vector");
        k.up = glm::normalize(*u);
    }
    k.target_elevation_deg = c.declared_number("target_elevation_deg");
    c.reject_unknown_keys();
    return k;
}

ShowKeyframe read_keyframe(const JsonReader& k, const SceneConfig& scene, const std::vector<ShowKeyframe>& before) {
    ShowKeyframe f;
    f.at_s = k.declared_number("at_s");
    if (!before.empty() && f.at_s <= before.back().at_s)
        k.fail("at_s", "keyframes must be in strictly increasing at_s");
    std::string utc = k.declared_string("time_utc");
    try {
        f.sim_time_s = utc_iso_to_j2000_seconds(utc);
    } catch (const std::invalid_argument& e) {
        k.fail("time_utc", e.what());
    }
    f.shadow_mode = optional_shadow_mode(k);
    f.camera_easing = easing_from_name(k.declared_choice("easing"));
    f.time_easing = easing_from_name(k.declared_choice("time_easing"));
    f.camera = read_camera(k.child("camera"), scene);
    k.reject_unknown_keys();
    return f;
}

// An event's "show" and "hide": lists of overlay names (common/overlay/overlay_kind.hpp). Returns
// whether it has any.
bool read_overlay_switches(const JsonReader& e, ShowEvent& ev) {
    bool any = false;
    for (const char* key : {"show", "hide"}) {
        for (const std::string& name : e.strings(key, {})) {
            try {
                ev.overlays[static_cast<size_t>(overlay_from_name(name))] = std::string(key) == "show";
            } catch (const std::invalid_argument& x) {
                e.fail(key, x.what());
            }
            any = true;
        }
    }
    return any;
}

ShowEvent read_event(const JsonReader& e) {
    ShowEvent ev;
    ev.at_s = e.declared_number("at_s");
    ev.shadow_mode = optional_shadow_mode(e);
    if (e.has("exposure")) {
        // A number in the first alternative of the declaration, or "auto".
        const nlohmann::json& number = e.declaration("exposure").at("oneOf").at(0);
        if (e.raw().at("exposure").is_string()) {
            e.one_of("exposure", {"auto"});
            ev.exposure_auto = true;
        } else {
            ev.exposure = static_cast<float>(
                e.number_in("exposure", number.at("minimum").get<double>(), number.at("maximum").get<double>()));
        }
    }
    if (e.has("star_magnitude_limit"))
        ev.star_magnitude_limit = static_cast<float>(e.declared_number("star_magnitude_limit", 0.0));
    if (e.has("pattern")) ev.pattern = alignment_pattern_from_name(e.one_of("pattern", e.declared_choices("pattern")));
    if (e.has("twinkle")) ev.twinkle = twinkle_mode_from_name(e.one_of("twinkle", e.declared_choices("twinkle")));
    if (e.has("sky_brightness") && e.has("bortle")) e.fail("bortle", "give sky_brightness or bortle, not both");
    if (e.has("sky_brightness")) ev.sky_brightness = e.declared_number("sky_brightness", 0.0);
    if (e.has("bortle"))
        ev.sky_brightness = bortle_zenith_mag_arcsec2(static_cast<int>(e.declared_integer("bortle", 0)));
    const bool overlays = read_overlay_switches(e, ev);
    e.reject_unknown_keys();
    if (!ev.shadow_mode && !ev.exposure && !ev.exposure_auto && !ev.star_magnitude_limit && !ev.pattern &&
        !ev.twinkle && !ev.sky_brightness && !overlays)
        e.fail("at_s",
               "an event must set at least one of shadow_mode, exposure, star_magnitude_limit, pattern, twinkle, "
               "sky_brightness, bortle, show, hide");
    return ev;
}

}  // namespace

ShowScript ShowScript::load(const std::string& file, const SceneConfig& scene) {
    const nlohmann::json doc = JsonReader::parse_file(file);
    JsonReader r(doc, file, &config_schema("show"));
    const double interval = r.declared_number("frame_interval_s");
    std::vector<ShowKeyframe> keys;
    auto list = r.array("keyframes");
    if (list.empty()) r.fail("keyframes", "at least one keyframe is required");
    for (auto& k : list) keys.push_back(read_keyframe(k, scene, keys));
    std::vector<ShowEvent> events;
    if (r.has("events"))
        for (auto& e : r.array("events")) events.push_back(read_event(e));
    r.reject_unknown_keys();
    ShowScript show(std::move(keys), interval, std::move(events));
    show.file_ = file;
    return show;
}

namespace {

struct CameraPose {
    glm::dvec3 position;
    glm::dquat orientation;
};

glm::dvec3 body_position(const SceneConfig& scene, uint16_t id, double t) {
    return body_state(scene.bodies.at(id), t).position_m;
}

// Unit direction of a surface site in the body frame (z = north pole, x = prime meridian):
// geodetic WGS84 latitude on the Earth (ERFA), spherical elsewhere.
glm::dvec3 site_direction(const BodyConfig& body, const ObserverSite& o) {
    const double lat = glm::radians(o.lat_deg), lon = glm::radians(o.lon_deg);
    if (body.ephemeris == "earth") {
        double xyz[3];
        if (eraGd2gc(ERFA_WGS84, lon, lat, 0.0, xyz) == 0) return glm::normalize(glm::dvec3(xyz[0], xyz[1], xyz[2]));
    }
    return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}

CameraPose pose_at(const CameraKey& k, const SceneConfig& scene, double t) {
    CameraPose p;
    glm::dvec3 fwd, up = k.up;
    if (k.observer && k.anchor) {
        // On the surface, turning with the body: local east-north-up from its orientation.
        const BodyConfig& body = scene.bodies.at(*k.anchor);
        const BodyState st = body_state(body, t);
        const glm::dmat3 to_world = glm::mat3_cast(st.orientation);
        const glm::dvec3 zenith = to_world * site_direction(body, *k.observer);
        p.position = st.position_m + zenith * (body.radius_m + k.observer->alt_m);
        glm::dvec3 north = to_world * glm::dvec3(0, 0, 1) - zenith * glm::dot(to_world * glm::dvec3(0, 0, 1), zenith);
        north =
            glm::length(north) > 1e-9 ? glm::normalize(north) : glm::normalize(glm::cross(zenith, glm::dvec3(0, 1, 0)));
        const glm::dvec3 east = glm::cross(north, zenith);
        const double az = glm::radians(k.observer->look_azimuth_deg), el = glm::radians(k.observer->look_elevation_deg);
        fwd = k.look_at ? body_position(scene, *k.look_at, t) - p.position
                        : std::cos(el) * (std::cos(az) * north + std::sin(az) * east) + std::sin(el) * zenith;
        up = zenith;
    } else {
        p.position = (k.anchor ? body_position(scene, *k.anchor, t) : glm::dvec3(0.0)) + k.offset_m;
        fwd = k.look_at ? body_position(scene, *k.look_at, t) - p.position : k.look_direction;
    }
    fwd = glm::length(fwd) > 0 ? glm::normalize(fwd) : glm::dvec3(0, 1, 0);
    if (std::abs(glm::dot(up, fwd)) > 0.999) up = std::abs(fwd.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    const glm::dvec3 right = glm::normalize(glm::cross(fwd, up));
    const glm::dvec3 cam_up = glm::cross(right, fwd);
    // Camera frame -> world: columns are the camera's +X, +Y, +Z (= -forward) in world axes.
    glm::dmat3 m(right, cam_up, -fwd);
    // Raise the target by turning the camera down about its own X axis.
    const double e = glm::radians(k.target_elevation_deg);
    const glm::dmat3 pitch(glm::dvec3(1, 0, 0), glm::dvec3(0, std::cos(-e), std::sin(-e)),
                           glm::dvec3(0, -std::sin(-e), std::cos(-e)));
    p.orientation = glm::normalize(glm::quat_cast(m * pitch));
    return p;
}

}  // namespace

Snapshot ShowScript::evaluate(double show_time_s, const SceneConfig& scene) const {
    size_t i = 0;
    while (i + 1 < keys_.size() && keys_[i + 1].at_s <= show_time_s) ++i;
    const ShowKeyframe& a = keys_[i];
    const ShowKeyframe& b = keys_[std::min(i + 1, keys_.size() - 1)];
    double f = 0.0;
    if (&a != &b) f = std::clamp((show_time_s - a.at_s) / (b.at_s - a.at_s), 0.0, 1.0);
    // Past the last keyframe time keeps running at the last segment's rate (or real time for one key).
    double rate = 1.0;
    if (keys_.size() > 1) {
        const auto& p = keys_[keys_.size() - 2];
        const auto& q = keys_.back();
        rate = (q.sim_time_s - p.sim_time_s) / (q.at_s - p.at_s);
    }
    double t = (&a == &b) ? a.sim_time_s + (show_time_s - a.at_s) * rate
                          : a.sim_time_s + ease(a.time_easing, f) * (b.sim_time_s - a.sim_time_s);

    Snapshot s;
    s.sim_time_s = t;
    const CameraPose pa = pose_at(a.camera, scene, t), pb = pose_at(b.camera, scene, t);
    const double smooth = ease(a.camera_easing, f);
    s.camera_position_m = pa.position + (pb.position - pa.position) * smooth;
    s.camera_orientation = glm::normalize(glm::slerp(pa.orientation, pb.orientation, smooth));
    for (const auto& body : scene.bodies) s.bodies.push_back(body_state(body, t));
    const ShowSettings settings = settings_at(show_time_s);
    s.settings.flags = with_shadow_mode(s.settings.flags, settings.shadow_mode.value_or(scene.shadows.mode));
    s.settings.flags = with_alignment_pattern(s.settings.flags, settings.pattern.value_or(AlignmentPattern::Off));
    s.settings.flags = with_twinkle_mode(s.settings.flags, settings.twinkle.value_or(scene.stars.twinkle));
    return s;
}

ShowSettings ShowScript::settings_at(double show_time_s) const {
    // Keyframes and events in show-time order; at equal times an event wins over a keyframe.
    ShowSettings out;
    size_t e = 0;
    auto apply_events_until = [&](double t, bool inclusive) {
        for (; e < events_.size() && (inclusive ? events_[e].at_s <= t : events_[e].at_s < t); ++e) {
            const ShowEvent& ev = events_[e];
            if (ev.shadow_mode) out.shadow_mode = ev.shadow_mode;
            if (ev.exposure) out.exposure = ev.exposure;
            if (ev.exposure_auto) out.exposure.reset();
            if (ev.star_magnitude_limit) out.star_magnitude_limit = ev.star_magnitude_limit;
            if (ev.pattern) out.pattern = ev.pattern;
            if (ev.twinkle) out.twinkle = ev.twinkle;
            if (ev.sky_brightness) out.sky_brightness = ev.sky_brightness;
            for (size_t k = 0; k < kOverlayCount; ++k)
                if (ev.overlays[k]) out.overlays[k] = ev.overlays[k];
        }
    };
    for (const auto& k : keys_) {
        if (k.at_s > show_time_s) break;
        apply_events_until(k.at_s, false);
        if (k.shadow_mode) out.shadow_mode = k.shadow_mode;
    }
    apply_events_until(show_time_s, true);
    return out;
}

double ShowScript::duration_s() const {
    double d = keys_.back().at_s;
    if (!events_.empty()) d = std::max(d, events_.back().at_s);
    return d;
}

}  // namespace cupola

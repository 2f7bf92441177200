#include "show_script.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "config/json_reader.hpp"
#include "scene/analytic_ephemeris.hpp"
#include "scene/sim_time.hpp"

namespace cupola {

ShowScript::ShowScript(std::vector<ShowKeyframe> keys, double frame_interval_s)
    : keys_(std::move(keys)), frame_interval_s_(frame_interval_s) {
    if (keys_.empty()) throw std::invalid_argument("a show needs at least one keyframe");
}

ShowScript ShowScript::load(const std::string& file, const SceneConfig& scene) {
    const nlohmann::json doc = JsonReader::parse_file(file);
    JsonReader r(doc, file, "");
    double interval = r.number_in("frame_interval_s", 1e-6, 1e9, 1.0 / 30.0);
    std::vector<ShowKeyframe> keys;
    auto body_id = [&](const JsonReader& c, const std::string& key) -> std::optional<uint16_t> {
        if (!c.has(key)) return std::nullopt;
        std::string name = c.string(key);
        if (name.empty()) return std::nullopt;
        const BodyConfig* b = scene.find(name);
        if (!b) c.fail(key, "no body named \"" + name + "\" in the scene " + scene.file);
        return b->id;
    };
    auto list = r.array("keyframes");
    if (list.empty()) r.fail("keyframes", "at least one keyframe is required");
    for (auto& k : list) {
        ShowKeyframe f;
        f.at_s = k.number_in("at_s", 0.0, 1e12);
        if (!keys.empty() && f.at_s <= keys.back().at_s) k.fail("at_s", "keyframes must be in strictly increasing at_s");
        std::string utc = k.string("time_utc");
        try {
            f.sim_time_s = utc_iso_to_j2000_seconds(utc);
        } catch (const std::invalid_argument& e) {
            k.fail("time_utc", e.what());
        }
        auto c = k.child("camera");
        f.camera.anchor = body_id(c, "anchor");
        f.camera.offset_m = c.optional_dvec3("offset_m").value_or(glm::dvec3(0.0));
        f.camera.look_at = body_id(c, "look_at");
        if (auto d = c.optional_dvec3("look_direction")) {
            if (f.camera.look_at) c.fail("look_direction", "give look_at or look_direction, not both");
            if (glm::length(*d) == 0.0) c.fail("look_direction", "must not be the zero vector");
            f.camera.look_direction = glm::normalize(*d);
        } else if (!f.camera.look_at) {
            c.fail("look_at", "missing: give look_at (a body) or look_direction");
        }
        if (auto u = c.optional_dvec3("up")) {
            if (glm::length(*u) == 0.0) c.fail("up", "must not be the zero vector");
            f.camera.up = glm::normalize(*u);
        }
        f.camera.target_elevation_deg = c.number_in("target_elevation_deg", -90.0, 90.0, 0.0);
        c.reject_unknown_keys();
        k.reject_unknown_keys();
        keys.push_back(f);
    }
    r.reject_unknown_keys();
    return ShowScript(std::move(keys), interval);
}

namespace {

struct CameraPose {
    glm::dvec3 position;
    glm::dquat orientation;
};

glm::dvec3 body_position(const SceneConfig& scene, uint16_t id, double t) {
    return analytic_body_state(scene.bodies.at(id), t).position_m;
}

CameraPose pose_at(const CameraKey& k, const SceneConfig& scene, double t) {
    CameraPose p;
    p.position = (k.anchor ? body_position(scene, *k.anchor, t) : glm::dvec3(0.0)) + k.offset_m;
    glm::dvec3 fwd = k.look_at ? body_position(scene, *k.look_at, t) - p.position : k.look_direction;
    fwd = glm::length(fwd) > 0 ? glm::normalize(fwd) : glm::dvec3(0, 1, 0);
    glm::dvec3 up = k.up;
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
                          : a.sim_time_s + f * (b.sim_time_s - a.sim_time_s);

    Snapshot s;
    s.sim_time_s = t;
    const CameraPose pa = pose_at(a.camera, scene, t), pb = pose_at(b.camera, scene, t);
    const double smooth = f * f * (3.0 - 2.0 * f);  // ease in and out between keyframes
    s.camera_position_m = pa.position + (pb.position - pa.position) * smooth;
    s.camera_orientation = glm::normalize(glm::slerp(pa.orientation, pb.orientation, smooth));
    for (const auto& body : scene.bodies) s.bodies.push_back(analytic_body_state(body, t));
    return s;
}

}  // namespace cupola

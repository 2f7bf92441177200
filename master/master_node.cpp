#include "master_node.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "control/control_server.hpp"
#include "director.hpp"
#include "frame_barrier.hpp"
#include "input/input_hub.hpp"
#include "input/input_latency.hpp"
#include "input/usb_input.hpp"
#include "tracking/dtrack_receiver.hpp"
#include "master_counters.hpp"
#include "present_skew.hpp"
#include "session/master_session.hpp"
#include "session/receive_until.hpp"
#include "net/key_file.hpp"
#include "net/wire_endpoint.hpp"
#include "util/stats_writer.hpp"
#include "util/monotonic_clock.hpp"
#include "scene/night_sky.hpp"
#include "wire/byte_io.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

MasterNode::MasterNode(ClusterConfig cluster, MasterOptions options)
    : cluster_(std::move(cluster)),
      scene_(load_scene_config(cluster_.scene_file)),
      show_(ShowScript::load(cluster_.show_file, scene_)),
      options_(std::move(options)),
      overlays_(scene_) {
    if (cluster_.output.auto_exposure.enabled || scene_.glare.enabled)
        atmospheres_ = std::make_unique<SceneAtmospheres>(scene_);
    auto_exposure_ = std::make_unique<AutoExposure>(cluster_, scene_, atmospheres_.get());
    if (scene_.glare.enabled) glare_sources_ = std::make_unique<GlareSources>(scene_, atmospheres_.get());
}

Snapshot make_frame_snapshot(const ClusterConfig& cluster, const SceneConfig& scene, const ShowScript& show,
                             uint64_t frame, const AutoExposure* auto_exposure, const GlareSources* glare) {
    const double dt = show_frame_interval_s(cluster, show);
    const double show_time_s = static_cast<double>(frame) * dt;
    Snapshot snap = show.evaluate(show_time_s, scene);
    finish_frame_snapshot(snap, show.settings_at(show_time_s), cluster, scene, frame, dt, auto_exposure, glare);
    snap.head.position_m = cluster.room.eye_m;  // untracked: the default eye, as a quiet master sends it
    return snap;
}

namespace {

// What the show, the presenter and the scene set for the frame: the star limit, the night sky's
// brightness and the overlays' opacities (without a fader, a frame on its own, each fully in or out).
void apply_sky_settings(Snapshot& snap, const ShowSettings& settings, const SceneConfig& scene, double frame_interval_s,
                        OverlayFader* overlays) {
    snap.settings.star_magnitude_limit =
        settings.star_magnitude_limit.value_or(static_cast<float>(scene.stars.magnitude_limit));
    const std::optional<double> sky_mag =
        settings.sky_brightness ? settings.sky_brightness : scene.stars.sky_brightness_mag_arcsec2;
    snap.settings.night_sky_cd_m2 = sky_mag ? static_cast<float>(sky_brightness_cd_m2(*sky_mag)) : 0.0f;
    const std::array<bool, kOverlayCount> shown = overlay_targets(settings, scene);
    if (overlays) {
        snap.settings.overlay_alpha = overlays->step(shown, frame_interval_s);
    } else {
        for (size_t k = 0; k < kOverlayCount; ++k) snap.settings.overlay_alpha[k] = shown[k] ? 1.0f : 0.0f;
    }
}

// The exposure, the display white, the eye's adaptation and night vision, metered from the
// snapshot as it stands (the night sky's glow included).
void apply_exposure(Snapshot& snap, const ShowSettings& settings, const ClusterConfig& cluster, double frame_interval_s,
                    const AutoExposure* auto_exposure, EyeAdaptation* eye) {
    ExposureDecision d;
    d.exposure = cluster.output.exposure;
    // The eye adapts whether or not the show fixes the exposure, so that a return to the
    // automatic exposure finds it where the view has kept it.
    if (auto_exposure && cluster.output.auto_exposure.enabled) d = auto_exposure->decide(snap, eye, frame_interval_s);
    if (settings.exposure) {  // a fixed exposure (a show's or the presenter's): linear, no curve
        d.exposure = *settings.exposure;
        d.tone_white = 0.0;
    }
    snap.settings.exposure = static_cast<float>(d.exposure);
    snap.settings.tone_white = static_cast<float>(d.tone_white);
    snap.settings.adapted_cd_m2 = static_cast<float>(d.adapted_cd_m2);
    // Night vision belongs to the eye's adaptation: only under the automatic exposure.
    const bool night = d.tone_white > 0.0 && d.adapted_cd_m2 > 0.0 && cluster.output.auto_exposure.night_vision;
    snap.settings.flags = night ? (snap.settings.flags | kNightVisionBit) : (snap.settings.flags & ~kNightVisionBit);
    const bool blur = night && cluster.output.auto_exposure.acuity_blur;
    snap.settings.flags = blur ? (snap.settings.flags | kAcuityBlurBit) : (snap.settings.flags & ~kAcuityBlurBit);
}

}  // namespace

void finish_frame_snapshot(Snapshot& snap, const ShowSettings& settings, const ClusterConfig& cluster,
                           const SceneConfig& scene, uint64_t frame, double frame_interval_s,
                           const AutoExposure* auto_exposure, const GlareSources* glare, EyeAdaptation* eye,
                           OverlayFader* overlays) {
    snap.frame = frame;
    apply_sky_settings(snap, settings, scene, frame_interval_s, overlays);
    apply_exposure(snap, settings, cluster, frame_interval_s, auto_exposure, eye);
    // The twinkle clock and the glare phase run on show time from the frame index, so they go on
    // in every mode; both wrap well before float loses the fractions that animate them.
    const double show_time_s = static_cast<double>(frame) * frame_interval_s;
    snap.settings.twinkle_time_s = static_cast<float>(std::fmod(show_time_s, 4096.0));
    if (glare && scene.glare.enabled) {
        snap.settings.glare_phase = static_cast<float>(std::fmod(show_time_s * scene.glare.animation_rate, 4096.0));
        snap.glare = glare->select(snap);
    }
}

namespace {

class EventLog {
public:
    explicit EventLog(const std::string& path) {
        if (path.empty()) return;
        out_.open(path, std::ios::trunc);
        if (!out_) throw std::runtime_error(path + ": cannot open the events file for writing");
    }
    void write(const nlohmann::json& j) {
        // Text from outside (control lines) may not be UTF-8: replaced, never fatal.
        if (out_) out_ << j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n' << std::flush;
    }

private:
    std::ofstream out_;
};

}  // namespace

namespace {

// The control channel (control/control_server.hpp). Before the first frame (the channels still
// joining, the start frame not known yet) only status, help and quit are answered; other commands
// wait for the first frame, and so does everything a client sent after one of them (replies stay
// in the order of the commands).
class ControlCommands {
public:
    explicit ControlCommands(const std::string& where) {
        if (where.empty()) return;
        server_ = std::make_unique<ControlServer>(where);
        spdlog::info("master: control commands on {}", where == "-" ? "standard input" : where);
    }

    void run(uint64_t next_frame, bool starting, Director& director, MasterCounters& counters, EventLog& events) {
        if (!server_) return;
        std::vector<ControlRequest> requests;
        if (!starting) {
            requests.swap(deferred_);
            deferring_clients_.clear();
        }
        for (auto& r : server_->take()) requests.push_back(std::move(r));
        for (const ControlRequest& req : requests) {
            std::optional<std::string> reply = answer(req, next_frame, starting, director, counters);
            if (!reply) continue;
            ++counters.control_commands;
            spdlog::info("master: control \"{}\" -> {}", req.line.substr(0, 200), reply->substr(0, 200));
            events.write(
                {{"event", "control"}, {"frame", next_frame}, {"line", req.line.substr(0, 200)}, {"reply", *reply}});
            server_->reply(req.client, *reply);
        }
    }

private:
    // The reply, or none when the request waits for the first frame.
    std::optional<std::string> answer(const ControlRequest& req, uint64_t next_frame, bool starting, Director& director,
                                      MasterCounters& counters) {
        try {
            if (starting && deferring_clients_.count(req.client)) {
                deferred_.push_back(req);
                return std::nullopt;
            }
            const ControlCommand cmd = parse_control_line(req.line);
            if (starting && cmd.verb != ControlVerb::Status && cmd.verb != ControlVerb::Help &&
                cmd.verb != ControlVerb::Quit) {
                deferred_.push_back(req);
                deferring_clients_.insert(req.client);
                return std::nullopt;
            }
            return "ok " + director.apply(cmd, next_frame);
        } catch (const std::exception& e) {  // ControlError, or anything a command ran into
            ++counters.control_errors;
            return std::string("error ") + e.what();
        }
    }

    std::unique_ptr<ControlServer> server_;
    std::vector<ControlRequest> deferred_;
    std::set<uint64_t> deferring_clients_;
};

// Navigation devices: a thread reads them (hotplug included) into the hub; each frame reads the
// hub once. None when the cluster has no USB input or it cannot start.
std::unique_ptr<UsbInput> start_usb_input(const ClusterConfig& cluster, InputHub& hub) {
    if (!cluster.input.usb) return nullptr;
    std::vector<DeviceModel> table = default_device_table();
    if (!cluster.input.device_table_file.empty())
        table = merge_device_tables(load_device_table(cluster.input.device_table_file), table);
    auto usb = std::make_unique<UsbInput>(std::move(table), hub);
    if (!usb->start()) usb.reset();
    return usb;
}

WireEndpoint open_announced_endpoint(const ClusterConfig& cluster, const AuthKey& key, uint64_t session) {
    WireEndpoint wire = open_master_endpoint(cluster, key, session);
    spdlog::info("master: session {:016x}", session);
    return wire;
}

std::vector<int> channel_ids(const ClusterConfig& cluster) {
    std::vector<int> ids;
    for (const auto& c : cluster.channels) ids.push_back(c.id);
    return ids;
}

nlohmann::json glare_json(const Snapshot& snap) {
    nlohmann::json glare = nlohmann::json::array();
    for (const auto& g : snap.glare)
        glare.push_back({{"body", g.body},
                         {"star", g.star},
                         {"visible_fraction", g.visible_fraction},
                         {"origin", g.origin == GlareOrigin::Measured ? "measured" : "analytic"},
                         {"measured_frame", g.measured_frame},
                         {"offset", {g.centroid_offset.x, g.centroid_offset.y, g.centroid_offset.z}}});
    return glare;
}

// The channels' reports of a frame for its event; logs when one rendered another snapshot.
nlohmann::json reports_json(const std::map<int, FrameReport>& reports, const std::string& hash, uint64_t frame) {
    nlohmann::json ch = nlohmann::json::object();
    bool hashes_agree = true;
    for (const auto& [id, rep] : reports) {
        ch[std::to_string(id)] = {{"hash", rep.snapshot_hash},        {"render_ms", rep.render_ms},
                                  {"write_ms", rep.write_ms},         {"latency_ms", rep.snapshot_received_ns / 1e6},
                                  {"rejected", rep.packets_rejected}, {"missed", rep.snapshots_missed}};
        if (rep.presentation) ch[std::to_string(id)]["ready_ns"] = rep.presentation->ready_ns;
        if (rep.snapshot_hash != hash) hashes_agree = false;
    }
    if (!hashes_agree) spdlog::error("master: frame {}: a channel reports another snapshot hash", frame);
    return ch;
}

}  // namespace

// One run of the master: the wire, the protocol session and what feeds the frames. run() is its
// steps: wait for the channels, resume, the frames (snapshot, barrier, pace), quit, the summary.
struct MasterNode::Loop {
    explicit Loop(MasterNode& n)
        : node(n),
          cluster(n.cluster_),
          key(load_key_file(cluster.key_file, cluster.network.strict_key_permissions)),
          session(new_session_nonce()),
          wire(open_announced_endpoint(cluster, key, session)),
          destinations(snapshot_destinations(cluster)),
          events(n.options_.events_file),
          control(n.options_.control),
          usb(start_usb_input(cluster, input_hub)),
          ids(channel_ids(cluster)),
          protocol(ids, session,
                   {std::chrono::milliseconds(cluster.network.resend_interval_ms),
                    std::chrono::milliseconds(cluster.network.channel_timeout_ms), cluster.network.swap_lock,
                    std::chrono::milliseconds(cluster.network.first_frame_timeout_ms)}),
          stats(n.options_.stats_file, "master"),
          director(cluster, n.scene_, n.show_),
          dtrack(cluster.room.tracking.source == TrackingSource::Dtrack
                     ? std::make_unique<DtrackReceiver>(cluster.room.tracking)
                     : nullptr),
          glare_sharing(cluster) {}

    bool stopped() const { return node.stop_requested_; }
    nlohmann::json stats_json() const;
    nlohmann::json presentation_json() const;
    nlohmann::json head_json() const;
    FrameHeadPose head_pose();
    void perform(const MasterActions& a);
    void step_until(Clock::time_point deadline);
    void wait_for_channels();
    void resume();
    void frames();
    bool frame(uint64_t f);
    nlohmann::json frame_event(const Snapshot& snap, const std::string& hash, uint64_t f, double frame_ms,
                               std::optional<double> input_ms) const;
    void pace(uint64_t f);
    void quit();
    void summary();

    MasterNode& node;
    const ClusterConfig& cluster;
    const AuthKey key;
    const uint64_t session;
    WireEndpoint wire;
    const std::vector<sockaddr_in> destinations;
    EventLog events;
    ControlCommands control;  // listens from the start; commands apply from the first frame on
    InputHub input_hub;
    InputLatency input_latency;
    std::unique_ptr<UsbInput> usb;
    const std::vector<int> ids;
    MasterSession protocol;
    StatsWriter stats;
    Director director;                       // who drives camera and clock (show or presenter)
    std::unique_ptr<DtrackReceiver> dtrack;  // room.tracking.source "dtrack"
    InputLatency head_latency;               // tracker datagram arrival -> the snapshot that carries it sent
    GlareSharing glare_sharing;
    std::map<int, FrameReport> previous_reports;  // the last frame's, for the glare visibility and the present skew
    PresentSkew present_skew;
    uint64_t current_frame = 0;
    uint64_t start_frame = 0;
    uint64_t frames_done = 0;
    uint64_t frames_incomplete = 0;
    Clock::time_point run_start;
};

nlohmann::json MasterNode::Loop::stats_json() const {
    return nlohmann::json{{"role", "master"},
                          {"session", fmt::format("{:016x}", session)},
                          {"frame", current_frame},
                          {"live", protocol.barrier().live_count()},
                          {"master", protocol.counters().to_json()},
                          {"presentation", presentation_json()},
                          {"usb", usb ? usb->counters().to_json() : nlohmann::json(nullptr)},
                          {"head", head_json()},
                          {"wire", wire.counters().to_json()}};
}

// The head tracking's counters and latency for --stats and the end event.
nlohmann::json MasterNode::Loop::head_json() const {
    nlohmann::json j = director.head().counters().to_json();
    j["source"] = tracking_source_names()[static_cast<size_t>(cluster.room.tracking.source)];
    if (head_latency.count())
        j["latency_ms"] = {{"frames", head_latency.count()},
                           {"median", head_latency.percentile(50)},
                           {"p99", head_latency.percentile(99)},
                           {"max", head_latency.percentile(100)}};
    return j;
}

// The frame's head pose: the tracker's datagrams read now, then the tracker's rules.
FrameHeadPose MasterNode::Loop::head_pose() {
    if (dtrack) dtrack->drain(director.head());
    return director.head().frame_pose(monotonic_ns());
}

// The swap lock's measurement (present_skew.hpp) for --stats and the end event.
nlohmann::json MasterNode::Loop::presentation_json() const {
    nlohmann::json j = present_skew.to_json();
    j["swap_lock"] = cluster.network.swap_lock;
    return j;
}

void MasterNode::Loop::perform(const MasterActions& a) {
    for (const MasterSend& s : a.sends) wire.send(s.type, s.frame, s.payload, destinations, s.to_session);
    for (const nlohmann::json& e : a.events) events.write(e);
}

// One step of every wait: receive until the deadline (at most one message, stepped through the
// session), then the session's time-driven rules, then the stats.
void MasterNode::Loop::step_until(Clock::time_point deadline) {
    if (auto m = receive_until(wire, deadline)) perform(protocol.on_message(*m, Clock::now()));
    perform(protocol.tick(Clock::now()));
    stats.tick([this] { return stats_json(); });
}

// Wait for the channels to say hello (and complete the handshake); status and quit are answered
// meanwhile.
void MasterNode::Loop::wait_for_channels() {
    const auto until = Clock::now() + milliseconds(cluster.network.hello_wait_ms);
    spdlog::info("master: waiting up to {} ms for {} channel(s)", cluster.network.hello_wait_ms, ids.size());
    while (!protocol.all_live() && Clock::now() < until && !stopped() && !director.quit_requested()) {
        control.run(0, true, director, protocol.counters(), events);
        step_until(until);
    }
    if (!protocol.all_live())
        spdlog::warn("master: starting with {} of {} channels; the others may join later",
                     protocol.barrier().live_count(), ids.size());
}

// Resume after the last frame that every joined channel rendered (a restarted master).
void MasterNode::Loop::resume() {
    if (!node.options_.resume) return;
    const std::optional<uint64_t> after = protocol.resume_after();
    if (!after) return;
    start_frame = *after + 1;
    spdlog::info("master: the channels already rendered up to frame {}: resuming the show at frame {}", *after,
                 start_frame);
    events.write({{"event", "resumed"}, {"frame", start_frame}});
}

void MasterNode::Loop::frames() {
    run_start = Clock::now();
    const auto& limit = node.options_.frames;
    for (uint64_t f = start_frame; !stopped() && (!limit || f < *limit); ++f) {
        current_frame = f;
        control.run(f, false, director, protocol.counters(), events);
        if (director.quit_requested() || !frame(f)) break;
        pace(f);
    }
}

// Frame f: its snapshot out, the barrier's wait, its event. False when stopped meanwhile.
bool MasterNode::Loop::frame(uint64_t f) {
    const DirectedFrame directed = director.frame(f, input_hub.combined());
    Snapshot snap = directed.snapshot;
    const FrameHeadPose head = head_pose();
    snap.head = head.pose;
    finish_frame_snapshot(snap, directed.settings, cluster, node.scene_, f, director.frame_interval_s(),
                          node.auto_exposure_.get(), node.glare_sources_.get(), &node.eye_, &node.overlays_);
    if (f > start_frame) glare_sharing.apply(snap, previous_reports, f - 1);
    std::vector<uint8_t> payload = encode_snapshot(snap);
    const std::string hash = snapshot_hash(payload);

    const auto frame_start = Clock::now();
    const uint64_t sent_ns = monotonic_ns();
    perform(protocol.start_frame(f, std::move(payload), frame_start, sent_ns));
    // Device report -> this snapshot on the wire: the presenter's latency, less the render.
    std::optional<double> input_ms;
    if (directed.input_used && directed.input_report_ns && sent_ns >= directed.input_report_ns)
        input_ms = input_latency.add(directed.input_report_ns, monotonic_ns());
    // Tracker datagram -> this snapshot on the wire.
    std::optional<double> head_ms;
    if (head.new_sample_arrival_ns) head_ms = head_latency.add(*head.new_sample_arrival_ns, monotonic_ns());
    while (!protocol.frame_complete() && !stopped()) step_until(protocol.next_wake());
    if (stopped()) return false;

    const std::map<int, FrameReport> reports = protocol.end_frame();
    const double frame_ms = std::chrono::duration<double, std::milli>(Clock::now() - frame_start).count();
    nlohmann::json fe = frame_event(snap, hash, f, frame_ms, input_ms);
    if (head_ms) fe["head_latency_ms"] = *head_ms;
    fe["channels"] = reports_json(reports, hash, f);
    if (auto shown = present_skew.add(reports, previous_reports)) fe["present"] = shown->to_json();
    events.write(fe);
    previous_reports = reports;
    ++frames_done;
    ++protocol.counters().frames;
    if (static_cast<int>(previous_reports.size()) < static_cast<int>(ids.size())) ++frames_incomplete;
    return true;
}

nlohmann::json MasterNode::Loop::frame_event(const Snapshot& snap, const std::string& hash, uint64_t f, double frame_ms,
                                             std::optional<double> input_ms) const {
    nlohmann::json fe{
        {"event", "frame"},
        {"frame", f},
        {"hash", hash},
        {"sim_time_s", snap.sim_time_s},
        {"frame_ms", frame_ms},
        {"live", protocol.barrier().live_count()},
        {"channels", nullptr},
        {"glare", glare_json(snap)},
        {"mode", director.live() ? "live" : "show"},
        {"camera_m", {snap.camera_position_m.x, snap.camera_position_m.y, snap.camera_position_m.z}},
        {"camera_q",
         {snap.camera_orientation.w, snap.camera_orientation.x, snap.camera_orientation.y, snap.camera_orientation.z}},
        {"flags", snap.settings.flags},
        {"exposure", snap.settings.exposure},
        {"tone_white", snap.settings.tone_white},
        {"adapted_cd_m2", snap.settings.adapted_cd_m2},
        {"head_m", {snap.head.position_m.x, snap.head.position_m.y, snap.head.position_m.z}},
        {"head_source", head_source_name(snap.head.source)}};
    if (input_ms) fe["input_latency_ms"] = *input_ms;
    return fe;
}

// At the configured frame rate, the rest of the frame's time passes here (a channel joining now
// renders the current frame).
void MasterNode::Loop::pace(uint64_t f) {
    if (cluster.frame_rate_hz <= 0) return;
    const auto next = run_start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>((f - start_frame + 1) / cluster.frame_rate_hz));
    while (Clock::now() < next) step_until(next);
}

void MasterNode::Loop::quit() {
    perform(protocol.start_quit(current_frame, Clock::now()));
    while (!protocol.quit_done()) step_until(protocol.next_wake());
    for (int id : protocol.unconfirmed_quits()) spdlog::warn("master: channel {} did not confirm quit", id);
}

void MasterNode::Loop::summary() {
    const double secs = std::chrono::duration<double>(Clock::now() - run_start).count();
    spdlog::info("master: {} frames in {:.2f} s ({:.2f} frames/s), {} with missing channels; wire: {}", frames_done,
                 secs, frames_done / std::max(secs, 1e-9), frames_incomplete, wire.counters().summary());
    if (present_skew.frames())
        spdlog::info("master: present skew over {} frames (swap lock {}): {}", present_skew.frames(),
                     cluster.network.swap_lock ? "on" : "off", present_skew.to_json()["skew_ms"].dump());
    if (input_latency.count()) spdlog::info("master: device report -> snapshot sent: {}", input_latency.summary());
    if (head_latency.count()) spdlog::info("master: tracker datagram -> snapshot sent: {}", head_latency.summary());
    if (node.glare_sources_)
        spdlog::info(
            "master: glare visibility: {} source-frames measured by the cluster, {} analytic ({} for a missing "
            "report)",
            glare_sharing.counts().measured, glare_sharing.counts().analytic, glare_sharing.counts().missing);
    stats.write_now(stats_json());
    events.write({{"event", "end"},
                  {"frames", frames_done},
                  {"seconds", secs},
                  {"rejected", wire.counters().total_rejected()},
                  {"wire", wire.counters().summary()},
                  {"stats", stats_json()}});
}

int MasterNode::run() {
    Loop loop(*this);
    loop.wait_for_channels();
    loop.resume();
    loop.frames();
    loop.quit();
    loop.summary();
    return 0;
}

}  // namespace cupola

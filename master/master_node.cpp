#include "master_node.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "control/control_server.hpp"
#include "director.hpp"
#include "frame_barrier.hpp"
#include "input/input_hub.hpp"
#include "input/input_latency.hpp"
#include "input/usb_input.hpp"
#include "master_counters.hpp"
#include "net/key_file.hpp"
#include "net/wire_endpoint.hpp"
#include "util/stats_writer.hpp"
#include "util/monotonic_clock.hpp"
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
      options_(std::move(options)) {
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
    return snap;
}

void finish_frame_snapshot(Snapshot& snap, const ShowSettings& settings, const ClusterConfig& cluster,
                           const SceneConfig& scene, uint64_t frame, double frame_interval_s,
                           const AutoExposure* auto_exposure, const GlareSources* glare) {
    snap.frame = frame;
    if (settings.exposure)
        snap.settings.exposure = *settings.exposure;
    else
        snap.settings.exposure =
            static_cast<float>(auto_exposure && cluster.output.auto_exposure.enabled ? auto_exposure->exposure(snap)
                                                                                     : cluster.output.exposure);
    snap.settings.star_magnitude_limit =
        settings.star_magnitude_limit.value_or(static_cast<float>(scene.stars.magnitude_limit));
    if (glare && scene.glare.enabled) {
        // The phase wraps well before float loses the fractions that animate the rays.
        const double t = static_cast<double>(frame) * frame_interval_s;
        snap.settings.glare_phase = static_cast<float>(std::fmod(t * scene.glare.animation_rate, 4096.0));
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

int MasterNode::run() {
    const AuthKey key = load_key_file(cluster_.key_file, cluster_.network.strict_key_permissions);
    const uint64_t session = new_session_nonce();
    WireEndpoint wire = open_master_endpoint(cluster_, key, session);
    const auto destinations = snapshot_destinations(cluster_);
    EventLog events(options_.events_file);
    spdlog::info("master: session {:016x}", session);
    // The control channel listens from the start; commands apply from the first frame on.
    std::unique_ptr<ControlServer> control;
    if (!options_.control.empty()) {
        control = std::make_unique<ControlServer>(options_.control);
        spdlog::info("master: control commands on {}", options_.control == "-" ? "standard input" : options_.control);
    }
    // Navigation devices: a thread reads them (hotplug included) into the hub; each frame reads
    // the hub once.
    InputHub input_hub;
    InputLatency input_latency;
    std::unique_ptr<UsbInput> usb;
    if (cluster_.input.usb) {
        std::vector<DeviceModel> table = default_device_table();
        if (!cluster_.input.device_table_file.empty())
            table = merge_device_tables(load_device_table(cluster_.input.device_table_file), table);
        usb = std::make_unique<UsbInput>(std::move(table), input_hub);
        if (!usb->start()) usb.reset();
    }

    std::vector<int> ids;
    for (const auto& c : cluster_.channels) ids.push_back(c.id);
    FrameBarrier barrier(ids, milliseconds(cluster_.network.channel_timeout_ms));
    MasterCounters counters;
    StatsWriter stats(options_.stats_file, "master");
    std::map<int, Clock::time_point> last_welcome;
    std::map<int, HelloMessage> hellos;  // the last verified hello of each channel's process
    std::set<int> quit_acked;
    uint64_t current_frame = 0;
    auto stats_json = [&] {
        return nlohmann::json{{"role", "master"},
                              {"session", fmt::format("{:016x}", session)},
                              {"frame", current_frame},
                              {"live", barrier.live_count()},
                              {"master", counters.to_json()},
                              {"usb", usb ? usb->counters().to_json() : nlohmann::json(nullptr)},
                              {"wire", wire.counters().to_json()}};
    };

    // Who drives camera and clock (show or presenter); commands from the control channel.
    Director director(cluster_, scene_, show_);
    // Before the first frame (the channels still joining, the start frame not known yet) only
    // status, help and quit are answered; other commands wait for the first frame, and so does
    // everything a client sent after one of them (replies stay in the order of the commands).
    std::vector<ControlRequest> deferred;
    std::set<uint64_t> deferring_clients;
    auto run_commands = [&](uint64_t next_frame, bool starting) {
        if (!control) return;
        std::vector<ControlRequest> requests;
        if (!starting) {
            requests.swap(deferred);
            deferring_clients.clear();
        }
        for (auto& r : control->take()) requests.push_back(std::move(r));
        for (const ControlRequest& req : requests) {
            std::string reply;
            try {
                if (starting && deferring_clients.count(req.client)) {
                    deferred.push_back(req);
                    continue;
                }
                const ControlCommand cmd = parse_control_line(req.line);
                if (starting && cmd.verb != ControlVerb::Status && cmd.verb != ControlVerb::Help &&
                    cmd.verb != ControlVerb::Quit) {
                    deferred.push_back(req);
                    deferring_clients.insert(req.client);
                    continue;
                }
                reply = "ok " + director.apply(cmd, next_frame);
            } catch (const std::exception& e) {  // ControlError, or anything a command ran into
                reply = std::string("error ") + e.what();
                ++counters.control_errors;
            }
            ++counters.control_commands;
            spdlog::info("master: control \"{}\" -> {}", req.line.substr(0, 200), reply.substr(0, 200));
            events.write(
                {{"event", "control"}, {"frame", next_frame}, {"line", req.line.substr(0, 200)}, {"reply", reply}});
            control->reply(req.client, reply);
        }
    };

    // Returns true when the channel (re)joined and must be sent the current snapshot again.
    auto handle = [&](const ReceivedMessage& rm, uint64_t frame, uint64_t sent_ns,
                      std::map<int, FrameReport>& reports) -> bool {
        const Message& m = rm.message;
        if (!barrier.known(m.sender)) {
            if (++counters.unknown_channel <= 3 || counters.unknown_channel % 100 == 0)
                spdlog::warn("master: message from unknown channel {} at {} ignored ({} so far)", m.sender,
                             to_string(rm.from), counters.unknown_channel);
            return false;
        }
        const auto now = Clock::now();
        try {
            if (m.type == PacketType::Hello) {
                const HelloMessage h = decode_hello(m.payload);
                if (h.channel != m.sender) throw WireError("hello names another channel than its sender");
                if (rm.to_session != session) {
                    // A process that has not seen this master's session yet: prove it is live now.
                    if (now - last_welcome[m.sender] >= milliseconds(20)) {
                        wire.send(PacketType::Welcome, frame, encode_welcome({h.channel, frame}), destinations,
                                  m.session);
                        last_welcome[m.sender] = now;
                        ++counters.welcomes_sent;
                    }
                    return false;
                }
                hellos[m.sender] = h;
                const bool was_live = barrier.state(m.sender) == ChannelState::Live;
                if (rm.opened)
                    barrier.on_restart(m.sender, now);
                else if (!barrier.on_alive(m.sender, now))
                    return false;
                ++counters.channel_joins;
                if (rm.opened && was_live) ++counters.channel_restarts;
                spdlog::info("master: channel {} joined (pid {}, {}){}", m.sender, h.process_id,
                             h.has_frame ? "last frame " + std::to_string(h.last_frame) : "no frame yet",
                             rm.opened && was_live ? ", a new process replacing a live one" : "");
                events.write({{"event", "channel_joined"},
                              {"channel", m.sender},
                              {"frame", frame},
                              {"pid", h.process_id},
                              {"new_process", rm.opened}});
                return true;
            }
            if (!rm.verified) return false;  // only hellos are answered before the handshake
            switch (m.type) {
                case PacketType::Heartbeat: {
                    if (!barrier.on_alive(m.sender, now)) return false;
                    ++counters.channel_joins;
                    events.write({{"event", "channel_joined"}, {"channel", m.sender}, {"frame", frame}});
                    return true;
                }
                case PacketType::FrameDone: {
                    FrameReport rep = decode_frame_report(m.payload);
                    if (rep.channel != m.sender) throw WireError("report names another channel than its sender");
                    const bool was_live = barrier.state(m.sender) == ChannelState::Live;
                    if (!barrier.on_report(m.sender, rep.frame, now)) {
                        ++counters.late_reports;
                        return false;
                    }
                    if (!was_live) {
                        ++counters.channel_joins;
                        events.write({{"event", "channel_joined"}, {"channel", m.sender}, {"frame", frame}});
                    }
                    if (sent_ns && rep.snapshot_received_ns >= sent_ns)
                        rep.snapshot_received_ns -= sent_ns;
                    else
                        rep.snapshot_received_ns = 0;
                    reports[m.sender] = rep;
                    return false;
                }
                case PacketType::QuitAck:
                    if (quit_acked.insert(m.sender).second) ++counters.quit_acks;
                    return false;
                default:
                    spdlog::warn("master: unexpected {} message from channel {}", packet_type_name(m.type), m.sender);
                    return false;
            }
        } catch (const WireError& e) {
            ++counters.malformed_messages;
            spdlog::warn("master: malformed {} from channel {}: {}", packet_type_name(m.type), m.sender, e.what());
            return false;
        }
    };

    // Wait for the channels to say hello (and complete the handshake).
    {
        std::map<int, FrameReport> unused;
        const auto until = Clock::now() + milliseconds(cluster_.network.hello_wait_ms);
        spdlog::info("master: waiting up to {} ms for {} channel(s)", cluster_.network.hello_wait_ms, ids.size());
        while (barrier.live_count() < static_cast<int>(ids.size()) && Clock::now() < until && !stop_requested_ &&
               !director.quit_requested()) {
            run_commands(0, true);  // status and quit answered while the channels join
            auto left = std::chrono::duration_cast<milliseconds>(until - Clock::now()).count();
            if (auto m = wire.receive(static_cast<int>(std::min<long long>(left, 100)))) handle(*m, 0, 0, unused);
            stats.tick(stats_json);
        }
        if (barrier.live_count() < static_cast<int>(ids.size()))
            spdlog::warn("master: starting with {} of {} channels; the others may join later", barrier.live_count(),
                         ids.size());
    }
    // Resume after the last frame that every joined channel rendered (a restarted master).
    uint64_t start_frame = 0;
    if (options_.resume) {
        std::optional<uint64_t> resume_after;
        for (const auto& [id, h] : hellos) {
            if (barrier.state(id) != ChannelState::Live) continue;
            if (!h.has_frame) {
                resume_after.reset();
                break;
            }
            resume_after = std::min(resume_after.value_or(h.last_frame), h.last_frame);
        }
        if (resume_after) {
            start_frame = *resume_after + 1;
            spdlog::info("master: the channels already rendered up to frame {}: resuming the show at frame {}",
                         *resume_after, start_frame);
            events.write({{"event", "resumed"}, {"frame", start_frame}});
        }
    }

    GlareSharing glare_sharing(cluster_);
    std::map<int, FrameReport> previous_reports;  // the last frame's, for the glare visibility
    const auto run_start = Clock::now();
    uint64_t frames_done = 0;
    uint64_t frames_incomplete = 0;
    for (uint64_t frame = start_frame; !stop_requested_ && (!options_.frames || frame < *options_.frames); ++frame) {
        current_frame = frame;
        run_commands(frame, false);
        if (director.quit_requested()) break;
        const DirectedFrame directed = director.frame(frame, input_hub.combined());
        Snapshot snap = directed.snapshot;
        finish_frame_snapshot(snap, directed.settings, cluster_, scene_, frame, director.frame_interval_s(),
                              auto_exposure_.get(), glare_sources_.get());
        if (frame > start_frame) glare_sharing.apply(snap, previous_reports, frame - 1);
        const std::vector<uint8_t> payload = encode_snapshot(snap);
        const std::string hash = snapshot_hash(payload);

        const auto frame_start = Clock::now();
        barrier.start_frame(frame, frame_start);
        const uint64_t sent_ns = monotonic_ns();
        wire.send(PacketType::Snapshot, frame, payload, destinations);
        ++counters.snapshots_sent;
        // Device report -> this snapshot on the wire: the presenter's latency, less the render.
        std::optional<double> input_ms;
        if (directed.input_used && directed.input_report_ns && sent_ns >= directed.input_report_ns)
            input_ms = input_latency.add(directed.input_report_ns, monotonic_ns());
        auto last_send = Clock::now();
        auto resend = [&] {
            wire.send(PacketType::Snapshot, frame, payload, destinations);
            ++counters.snapshot_resends;
            last_send = Clock::now();
        };
        std::map<int, FrameReport> reports;

        while (!barrier.complete() && !stop_requested_) {
            const auto resend_at = last_send + milliseconds(cluster_.network.resend_interval_ms);
            const auto wake = std::min(resend_at, barrier.next_deadline());
            auto wait = std::chrono::duration_cast<milliseconds>(wake - Clock::now()).count();
            if (auto m = wire.receive(static_cast<int>(std::clamp<long long>(wait, 0, 1000))))
                if (handle(*m, frame, sent_ns, reports)) resend();  // a (re)joined channel renders this frame
            const auto now = Clock::now();
            for (int id : barrier.expire(now)) {
                ++counters.channel_drops;
                spdlog::warn("master: channel {} silent for {} ms at frame {}: dropped, the others go on", id,
                             cluster_.network.channel_timeout_ms, frame);
                events.write({{"event", "channel_dropped"}, {"channel", id}, {"frame", frame}});
            }
            // A lost datagram costs a resend, not the session.
            if (!barrier.complete() && now >= last_send + milliseconds(cluster_.network.resend_interval_ms)) resend();
            stats.tick(stats_json);
        }
        if (stop_requested_) break;

        nlohmann::json ch = nlohmann::json::object();
        bool hashes_agree = true;
        for (const auto& [id, rep] : reports) {
            ch[std::to_string(id)] = {
                {"hash", rep.snapshot_hash},        {"render_ms", rep.render_ms},
                {"write_ms", rep.write_ms},         {"latency_ms", rep.snapshot_received_ns / 1e6},
                {"rejected", rep.packets_rejected}, {"missed", rep.snapshots_missed}};
            if (rep.snapshot_hash != hash) hashes_agree = false;
        }
        if (!hashes_agree) spdlog::error("master: frame {}: a channel reports another snapshot hash", frame);
        nlohmann::json glare = nlohmann::json::array();
        for (const auto& g : snap.glare)
            glare.push_back({{"body", g.body},
                             {"star", g.star},
                             {"visible_fraction", g.visible_fraction},
                             {"origin", g.origin == GlareOrigin::Measured ? "measured" : "analytic"},
                             {"measured_frame", g.measured_frame},
                             {"offset", {g.centroid_offset.x, g.centroid_offset.y, g.centroid_offset.z}}});
        previous_reports = std::move(reports);
        const double frame_ms = std::chrono::duration<double, std::milli>(Clock::now() - frame_start).count();
        nlohmann::json fe{{"event", "frame"},
                          {"frame", frame},
                          {"hash", hash},
                          {"sim_time_s", snap.sim_time_s},
                          {"frame_ms", frame_ms},
                          {"live", barrier.live_count()},
                          {"channels", ch},
                          {"glare", glare},
                          {"mode", director.live() ? "live" : "show"},
                          {"camera_m", {snap.camera_position_m.x, snap.camera_position_m.y, snap.camera_position_m.z}},
                          {"camera_q",
                           {snap.camera_orientation.w, snap.camera_orientation.x, snap.camera_orientation.y,
                            snap.camera_orientation.z}},
                          {"flags", snap.settings.flags},
                          {"exposure", snap.settings.exposure}};
        if (input_ms) fe["input_latency_ms"] = *input_ms;
        events.write(fe);
        ++frames_done;
        ++counters.frames;
        if (static_cast<int>(previous_reports.size()) < static_cast<int>(ids.size())) ++frames_incomplete;

        if (cluster_.frame_rate_hz > 0) {
            const auto next = run_start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                                              (frame - start_frame + 1) / cluster_.frame_rate_hz));
            while (Clock::now() < next) {
                std::map<int, FrameReport> late;
                auto left = std::chrono::duration_cast<milliseconds>(next - Clock::now()).count();
                if (auto m = wire.receive(static_cast<int>(std::clamp<long long>(left, 0, 100))))
                    if (handle(*m, frame, 0, late)) resend();  // joined between frames: it renders the current one
                stats.tick(stats_json);
            }
        }
    }

    // Tell the slaves to quit, again every 50 ms until every live channel confirmed (at most 2 s):
    // a lost datagram must not leave one running.
    {
        const uint64_t quit_frame = current_frame + 1;
        const auto until = Clock::now() + milliseconds(2000);
        std::map<int, FrameReport> unused;
        auto all_acked = [&] {
            for (int id : ids)
                if (barrier.state(id) == ChannelState::Live && !quit_acked.count(id)) return false;
            return true;
        };
        while (!all_acked() && Clock::now() < until) {
            wire.send(PacketType::Quit, quit_frame, {}, destinations);
            const auto round_end = Clock::now() + milliseconds(50);
            while (Clock::now() < round_end)
                if (auto m = wire.receive(static_cast<int>(std::max<long long>(
                        0, std::chrono::duration_cast<milliseconds>(round_end - Clock::now()).count()))))
                    handle(*m, current_frame, 0, unused);
        }
        for (int id : ids)
            if (barrier.state(id) == ChannelState::Live && !quit_acked.count(id))
                spdlog::warn("master: channel {} did not confirm quit", id);
    }
    const double secs = std::chrono::duration<double>(Clock::now() - run_start).count();
    spdlog::info("master: {} frames in {:.2f} s ({:.2f} frames/s), {} with missing channels; wire: {}", frames_done,
                 secs, frames_done / std::max(secs, 1e-9), frames_incomplete, wire.counters().summary());
    if (input_latency.count()) spdlog::info("master: device report -> snapshot sent: {}", input_latency.summary());
    if (glare_sources_)
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
    return 0;
}

}  // namespace cupola

#include "master_node.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "frame_barrier.hpp"
#include "net/wire_endpoint.hpp"
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
    const double dt = cluster.frame_rate_hz > 0 ? 1.0 / cluster.frame_rate_hz : show.frame_interval_s();
    const double show_time_s = static_cast<double>(frame) * dt;
    Snapshot snap = show.evaluate(show_time_s, scene);
    snap.frame = frame;
    snap.settings.exposure = static_cast<float>(
        auto_exposure && cluster.output.auto_exposure.enabled ? auto_exposure->exposure(snap) : cluster.output.exposure);
    snap.settings.star_magnitude_limit = static_cast<float>(scene.stars.magnitude_limit);
    if (glare && scene.glare.enabled) {
        // The phase wraps well before float loses the fractions that animate the rays.
        snap.settings.glare_phase = static_cast<float>(std::fmod(show_time_s * scene.glare.animation_rate, 4096.0));
        snap.glare = glare->select(snap);
    }
    return snap;
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
        if (out_) out_ << j.dump() << '\n' << std::flush;
    }

private:
    std::ofstream out_;
};

}  // namespace

int MasterNode::run() {
    const AuthKey key = load_key_file(cluster_.key_file);
    WireEndpoint wire = open_master_endpoint(cluster_, key);
    const auto destinations = snapshot_destinations(cluster_);
    EventLog events(options_.events_file);

    std::vector<int> ids;
    for (const auto& c : cluster_.channels) ids.push_back(c.id);
    FrameBarrier barrier(ids, milliseconds(cluster_.network.channel_timeout_ms));

    auto handle = [&](const ReceivedMessage& rm, uint64_t current_frame, uint64_t sent_ns,
                      std::map<int, FrameReport>& reports) -> bool /* rejoined */ {
        const Message& m = rm.message;
        if (!barrier.known(m.sender)) {
            spdlog::warn("master: message from unknown channel {} at {} ignored", m.sender, to_string(rm.from));
            return false;
        }
        const auto now = Clock::now();
        try {
            switch (m.type) {
                case PacketType::Hello: {
                    HelloMessage h = decode_hello(m.payload);
                    if (h.channel != m.sender) throw WireError("hello names another channel than its sender");
                    bool rejoined = barrier.on_alive(m.sender, now);
                    if (rejoined) {
                        spdlog::info("master: channel {} joined (pid {}, last frame {})", m.sender, h.process_id, h.last_frame);
                        events.write({{"event", "channel_joined"}, {"channel", m.sender}, {"frame", current_frame},
                                      {"pid", h.process_id}});
                    }
                    return rejoined;
                }
                case PacketType::Heartbeat: {
                    bool rejoined = barrier.on_alive(m.sender, now);
                    if (rejoined)
                        events.write({{"event", "channel_joined"}, {"channel", m.sender}, {"frame", current_frame}});
                    return rejoined;
                }
                case PacketType::FrameDone: {
                    FrameReport rep = decode_frame_report(m.payload);
                    if (rep.channel != m.sender) throw WireError("report names another channel than its sender");
                    const bool was_live = barrier.state(m.sender) == ChannelState::Live;
                    if (barrier.on_report(m.sender, rep.frame, now)) {
                        if (!was_live) events.write({{"event", "channel_joined"}, {"channel", m.sender}, {"frame", current_frame}});
                        if (sent_ns && rep.snapshot_received_ns >= sent_ns) rep.snapshot_received_ns -= sent_ns;
                        else rep.snapshot_received_ns = 0;
                        reports[m.sender] = rep;
                        return !was_live;
                    }
                    return false;
                }
                default:
                    spdlog::warn("master: unexpected {} message from channel {}", packet_type_name(m.type), m.sender);
                    return false;
            }
        } catch (const WireError& e) {
            spdlog::warn("master: malformed {} from channel {}: {}", packet_type_name(m.type), m.sender, e.what());
            return false;
        }
    };

    // Wait for the channels to say hello.
    {
        std::map<int, FrameReport> unused;
        const auto until = Clock::now() + milliseconds(cluster_.network.hello_wait_ms);
        spdlog::info("master: waiting up to {} ms for {} channel(s)", cluster_.network.hello_wait_ms, ids.size());
        while (barrier.live_count() < static_cast<int>(ids.size()) && Clock::now() < until && !stop_requested_) {
            auto left = std::chrono::duration_cast<milliseconds>(until - Clock::now()).count();
            if (auto m = wire.receive(static_cast<int>(std::min<long long>(left, 100)))) handle(*m, 0, 0, unused);
        }
        if (barrier.live_count() < static_cast<int>(ids.size()))
            spdlog::warn("master: starting with {} of {} channels; the others may join later", barrier.live_count(), ids.size());
    }

    GlareSharing glare_sharing(cluster_);
    std::map<int, FrameReport> previous_reports;  // the last frame's, for the glare visibility
    const auto run_start = Clock::now();
    uint64_t frames_done = 0;
    uint64_t frames_incomplete = 0;
    for (uint64_t frame = 0; !stop_requested_ && (!options_.frames || frame < *options_.frames); ++frame) {
        Snapshot snap = make_frame_snapshot(cluster_, scene_, show_, frame, auto_exposure_.get(), glare_sources_.get());
        if (frame > 0) glare_sharing.apply(snap, previous_reports, frame - 1);
        const std::vector<uint8_t> payload = encode_snapshot(snap);
        const std::string hash = snapshot_hash(payload);

        const auto frame_start = Clock::now();
        barrier.start_frame(frame, frame_start);
        const uint64_t sent_ns = monotonic_ns();
        wire.send(PacketType::Snapshot, frame, payload, destinations);
        auto last_send = Clock::now();
        std::map<int, FrameReport> reports;
        std::vector<int> dropped_now;

        while (!barrier.complete() && !stop_requested_) {
            const auto resend_at = last_send + milliseconds(cluster_.network.resend_interval_ms);
            const auto wake = std::min(resend_at, barrier.next_deadline());
            auto wait = std::chrono::duration_cast<milliseconds>(wake - Clock::now()).count();
            if (auto m = wire.receive(static_cast<int>(std::clamp<long long>(wait, 0, 1000)))) {
                if (handle(*m, frame, sent_ns, reports)) {
                    // A (re)joined channel renders the current frame: send it again now.
                    wire.send(PacketType::Snapshot, frame, payload, destinations);
                    last_send = Clock::now();
                }
            }
            const auto now = Clock::now();
            for (int id : barrier.expire(now)) {
                spdlog::warn("master: channel {} silent for {} ms at frame {}: dropped, the others go on", id,
                             cluster_.network.channel_timeout_ms, frame);
                events.write({{"event", "channel_dropped"}, {"channel", id}, {"frame", frame}});
                dropped_now.push_back(id);
            }
            if (!barrier.complete() && now >= last_send + milliseconds(cluster_.network.resend_interval_ms)) {
                // A lost datagram costs a resend, not the session.
                wire.send(PacketType::Snapshot, frame, payload, destinations);
                last_send = now;
            }
        }
        if (stop_requested_) break;

        nlohmann::json ch = nlohmann::json::object();
        bool hashes_agree = true;
        for (const auto& [id, rep] : reports) {
            ch[std::to_string(id)] = {{"hash", rep.snapshot_hash},
                                      {"render_ms", rep.render_ms},
                                      {"write_ms", rep.write_ms},
                                      {"latency_ms", rep.snapshot_received_ns / 1e6},
                                      {"rejected", rep.packets_rejected},
                                      {"missed", rep.snapshots_missed}};
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
        events.write({{"event", "frame"}, {"frame", frame}, {"hash", hash}, {"sim_time_s", snap.sim_time_s},
                      {"frame_ms", frame_ms}, {"live", barrier.live_count()}, {"channels", ch}, {"glare", glare}});
        ++frames_done;
        if (static_cast<int>(previous_reports.size()) < static_cast<int>(ids.size())) ++frames_incomplete;

        if (cluster_.frame_rate_hz > 0) {
            const auto next = run_start + std::chrono::duration_cast<Clock::duration>(
                                              std::chrono::duration<double>((frame + 1) / cluster_.frame_rate_hz));
            while (Clock::now() < next) {
                std::map<int, FrameReport> late;
                auto left = std::chrono::duration_cast<milliseconds>(next - Clock::now()).count();
                if (auto m = wire.receive(static_cast<int>(std::clamp<long long>(left, 0, 100))))
                    if (handle(*m, frame, 0, late))  // joined between frames: it renders the current one
                        wire.send(PacketType::Snapshot, frame, payload, destinations);
            }
        }
    }

    // Tell the slaves to quit (several times: a lost datagram must not leave one running).
    for (int i = 0; i < 5; ++i) {
        wire.send(PacketType::Quit, frames_done, {}, destinations);
        std::this_thread::sleep_for(milliseconds(20));
    }
    const double secs = std::chrono::duration<double>(Clock::now() - run_start).count();
    spdlog::info("master: {} frames in {:.2f} s ({:.2f} frames/s), {} with missing channels; wire: {}", frames_done,
                 secs, frames_done / std::max(secs, 1e-9), frames_incomplete, wire.counters().summary());
    if (glare_sources_)
        spdlog::info("master: glare visibility: {} source-frames measured by the cluster, {} analytic ({} for a missing "
                     "report)",
                     glare_sharing.counts().measured, glare_sharing.counts().analytic, glare_sharing.counts().missing);
    events.write({{"event", "end"}, {"frames", frames_done}, {"seconds", secs},
                  {"rejected", wire.counters().total_rejected()}, {"wire", wire.counters().summary()}});
    return 0;
}

}  // namespace cupola

#include "slave_node.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <optional>

#include "calibration/channel_warp.hpp"
#include "image/frame_image.hpp"
#include "net/key_file.hpp"
#include "net/wire_endpoint.hpp"
#include "output/output_surface.hpp"
#include "output/projector_output.hpp"
#include "scene_renderer.hpp"
#include "session/receive_until.hpp"
#include "session/slave_session.hpp"
#include "startup_prefetch.hpp"
#include "util/monotonic_clock.hpp"
#include "util/stats_writer.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

using Clock = std::chrono::steady_clock;

SlaveNode::SlaveNode(ClusterConfig cluster, int channel_id, SlaveOptions options)
    : cluster_(std::move(cluster)), channel_(cluster_.channel(channel_id)), options_(std::move(options)) {
    if (options_.formats.empty()) options_.formats = cluster_.output.formats;
    if (options_.egl_device == -2) options_.egl_device = cluster_.egl_device;
}

namespace {

// The channel's projector calibration (channels[].calibration), read once at start-up: the warp
// and blend the output stage applies. None: the projector shows the channel render as it is.
std::optional<ProjectorWarp> channel_warp(const ChannelConfig& channel) {
    if (!channel.calibration) return std::nullopt;
    return load_channel_warp(*channel.calibration);
}

// The channel's frame: its render, both eyes of a packed stereo pair.
glm::ivec2 frame_size(const ChannelConfig& c) { return stereo_frame_size(c.stereo, c.width, c.height); }

// The frustum the output's acuity blur follows; none for a frame of two eyes side by side.
std::optional<ChannelFrustum> content_view(const ChannelConfig& c) {
    if (stereo_eye_count(c.stereo) == 2 && c.stereo != StereoMode::Anaglyph) return std::nullopt;
    return c.frustum();
}

// The output surface and its EGL context (headless, an X11 window or a KMS output, from the
// channel's sinks), named in the log as soon as it is up. A live output shows the projector
// raster: the calibration's, else the channel's frame (both eyes of a packed stereo frame).
struct LoggedSurface {
    LoggedSurface(const ChannelConfig& channel, int device, const std::optional<ProjectorWarp>& warp)
        : surface(channel.output, device, warp ? warp->raster_width : frame_size(channel).x,
                  warp ? warp->raster_height : frame_size(channel).y),
          context(surface.egl()) {
        const auto& i = context.info();
        spdlog::info("slave {}: EGL {} (device {} of {}), {} / {}", channel.name, i.platform, i.device_index,
                     i.device_count, i.renderer, i.version);
    }
    OutputSurface surface;
    const EglContext& context;
};

SlaveSessionConfig session_config(const ChannelConfig& channel, const SlaveOptions& options, const SceneConfig& scene,
                                  bool swap_lock) {
    SlaveSessionConfig c;
    c.channel = channel.id;
    c.process_id = static_cast<uint32_t>(::getpid());
    c.idle_timeout = std::chrono::seconds(options.idle_timeout_s);
    c.scene_body_count = scene.bodies.size();
    c.scene_file = scene.file;
    c.log_name = "slave " + channel.name;
    c.swap_lock = swap_lock;
    return c;
}

// --present-log: one JSON line per frame shown.
class PresentLog {
public:
    explicit PresentLog(const std::string& path) {
        if (path.empty()) return;
        out_.open(path, std::ios::trunc);
        if (!out_) throw std::runtime_error(path + ": cannot open the present log for writing");
    }
    void write(int channel, const PresentJob& job, uint64_t present_ns) {
        if (!out_) return;
        out_ << nlohmann::json{{"channel", channel},
                               {"frame", job.frame},
                               {"ready_ns", job.ready_ns},
                               {"present_ns", present_ns},
                               {"cause", present_cause_name(job.cause)}}
                    .dump()
             << '\n'
             << std::flush;
    }

private:
    std::ofstream out_;
};

}  // namespace

// One run of a slave: EGL, renderer, wire and the protocol session. run() is its steps: the
// session's time-driven rules, receive until its next wake, one received message through the
// session, render and report what it hands out.
struct SlaveNode::Loop {
    Loop(SlaveNode& n, Clock::time_point started)
        : node(n),
          channel(n.channel_),
          key(load_key_file(n.cluster_.key_file, n.cluster_.network.strict_key_permissions)),
          scene(load_scene_config(n.cluster_.scene_file)),
          prefetch(scene),
          warp(channel_warp(channel)),
          gl(channel, n.options_.egl_device, warp),
          renderer(n.cluster_, channel, scene),
          output(gl.surface, channel.output, FilesOutput{n.options_.out_dir, n.options_.formats}, warp,
                 frame_size(channel).x, frame_size(channel).y, content_view(channel)),
          session(new_session_nonce()),
          wire(open_slave_endpoint(n.cluster_, channel, key, session)),
          master(master_report_address(n.cluster_)),
          log_name("slave " + channel.name),
          stats(n.options_.stats_file, log_name),
          protocol(session_config(channel, n.options_, scene, n.cluster_.network.swap_lock), Clock::now()),
          present_log(n.options_.present_log) {
        spdlog::info("slave {}: ready to join {:.0f} ms after start (session {:016x})", channel.name,
                     std::chrono::duration<double, std::milli>(Clock::now() - started).count(), session);
    }

    nlohmann::json stats_json() const;
    nlohmann::json output_json() const;
    int run();
    void receive();
    std::optional<int> perform(SlaveActions a, uint64_t received_ns = 0);
    void render_and_report(const RenderJob& job, uint64_t received_ns);
    void present(const PresentJob& job);
    int finish(int code);

    SlaveNode& node;
    const ChannelConfig& channel;
    const AuthKey key;
    const SceneConfig scene;
    StartupPrefetch prefetch;  // the maps and the eclipse table, while EGL starts
    const std::optional<ProjectorWarp> warp;
    LoggedSurface gl;
    SceneRenderer renderer;
    ProjectorOutput output;
    const uint64_t session;
    WireEndpoint wire;
    const sockaddr_in master;
    const std::string log_name;
    StatsWriter stats;
    SlaveSession protocol;
    PresentLog present_log;
};

nlohmann::json SlaveNode::Loop::stats_json() const {
    return nlohmann::json{{"role", "slave"},
                          {"channel", channel.id},
                          {"session", fmt::format("{:016x}", session)},
                          {"master_session", fmt::format("{:016x}", wire.peer_session(kMasterSender))},
                          {"slave", protocol.counters().to_json()},
                          {"output", output_json()},
                          {"wire", wire.counters().to_json()}};
}

// The output stage: its sinks, how often a frame was read back to the CPU and presented.
nlohmann::json SlaveNode::Loop::output_json() const {
    return nlohmann::json{{"sinks", output.sink_names()},
                          {"warp_pass", output.warps()},
                          {"read_backs", renderer.read_backs() + output.read_backs()},
                          {"presents", output.presents()}};
}

int SlaveNode::Loop::run() {
    while (!node.stop_requested_) {
        if (auto code = perform(protocol.tick(Clock::now()))) return finish(*code);
        stats.tick([this] { return stats_json(); });
        receive();
        const uint64_t received_ns = monotonic_ns();
        if (auto code = perform(protocol.step(Clock::now()), received_ns)) return finish(*code);
    }
    return finish(0);
}

// Waits for a message when none is queued; then queues everything already in the socket, so that
// after a stall the session renders only the newest snapshot.
void SlaveNode::Loop::receive() {
    if (!protocol.has_queued())
        if (auto m = receive_until(wire, protocol.next_wake(Clock::now()))) protocol.receive(std::move(*m));
    if (!protocol.has_queued()) return;
    while (auto more = receive_queued(wire)) protocol.receive(std::move(*more));
}

std::optional<int> SlaveNode::Loop::perform(SlaveActions a, uint64_t received_ns) {
    for (const SlaveSend& s : a.sends) wire.send(s.type, s.frame, s.payload, {master}, s.to_session);
    if (a.present) present(*a.present);
    if (a.render) render_and_report(*a.render, received_ns);
    if (a.exit_code == 0)
        spdlog::info("slave {}: master says quit after {} frames; stats {}", channel.name,
                     protocol.counters().frames_rendered, stats_json().dump());
    return a.exit_code;
}

void SlaveNode::Loop::render_and_report(const RenderJob& job, uint64_t received_ns) {
    const Snapshot& snap = job.snapshot;
    const auto t0 = Clock::now();
    renderer.draw(snap);
    const auto t1 = Clock::now();
    FrameMetadata meta;
    meta.channel_id = channel.id;
    meta.channel_name = channel.name;
    meta.frame = snap.frame;
    meta.sim_time_s = snap.sim_time_s;
    meta.snapshot_hash = job.hash;
    meta.renderer = gl.context.info().renderer;
    meta.tone_white = snap.settings.tone_white;
    meta.adapted_cd_m2 = snap.settings.adapted_cd_m2;
    meta.night_vision = night_vision_of(snap.settings.flags);
    meta.acuity_blur = acuity_blur_of(snap.settings.flags);
    // The warp pass and every sink's take, then settle: "ready N" goes out only once frame N's
    // files are on disk. The master counts a frame done when every channel reported it, and a
    // channel that restarts renders the master's current frame, not older ones (master/session/
    // master_session.cpp): a report sent before the write would lose the frame to a crash in
    // between. write_ms is the time from the take to the files written (0 without a files sink).
    const double wait_ms = output.take(renderer, meta, snap.settings.exposure) + output.settle();

    FrameReport rep;
    rep.render_ms = std::chrono::duration<float, std::milli>(t1 - t0).count();
    rep.write_ms = static_cast<float>(wait_ms);
    rep.snapshot_received_ns = received_ns;
    rep.glare = renderer.glare_measurements();         // this frame's queries, for the next snapshot
    rep.presentation = PresentTiming{monotonic_ns()};  // ready to show
    const float render_ms = rep.render_ms, write_ms = rep.write_ms;
    perform(protocol.rendered(std::move(rep), wire.counters().total_rejected()));
    spdlog::debug("slave {}: frame {} rendered in {:.1f} ms, queued for writing after {:.1f} ms", channel.name,
                  snap.frame, render_ms, write_ms);
}

// Wait for present, then present: the session holds a reported frame until the master's present
// (or what implies it) arrives through the loop's receive step, and hands it here; with the swap
// lock off it hands it at once. The output swaps; its time goes into the next report.
void SlaveNode::Loop::present(const PresentJob& job) {
    const uint64_t present_ns = output.present(job.frame);  // live sinks swap
    protocol.presented(job.frame, present_ns);
    present_log.write(channel.id, job, present_ns);
}

// On every way out: the frames already rendered reach the disk before the process ends.
int SlaveNode::Loop::finish(int code) {
    const uint64_t failed = output.finish();
    stats.write_now(stats_json());
    if (failed > 0) {
        spdlog::error("slave {}: {} frame(s) could not be written", channel.name, failed);
        return code == 0 ? 4 : code;
    }
    return code;
}

int SlaveNode::run() {
    const auto started = Clock::now();
    Loop loop(*this, started);
    return loop.run();
}

}  // namespace cupola

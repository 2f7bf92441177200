#include "slave_node.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <deque>
#include <optional>

#include "async_frame_writer.hpp"
#include "gl/egl_context.hpp"
#include "image/frame_image.hpp"
#include "net/key_file.hpp"
#include "net/wire_endpoint.hpp"
#include "scene_renderer.hpp"
#include "slave_counters.hpp"
#include "util/stats_writer.hpp"
#include "util/monotonic_clock.hpp"
#include "wire/byte_io.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

SlaveNode::SlaveNode(ClusterConfig cluster, int channel_id, SlaveOptions options)
    : cluster_(std::move(cluster)), channel_(cluster_.channel(channel_id)), options_(std::move(options)) {
    if (options_.formats.empty()) options_.formats = cluster_.output.formats;
    if (options_.egl_device == -2) options_.egl_device = cluster_.egl_device;
}

int SlaveNode::run() {
    const auto started = Clock::now();
    const AuthKey key = load_key_file(cluster_.key_file, cluster_.network.strict_key_permissions);
    const SceneConfig scene = load_scene_config(cluster_.scene_file);
    EglContext gl(options_.egl_device);
    spdlog::info("slave {}: EGL {} (device {} of {}), {} / {}", channel_.name, gl.info().platform,
                 gl.info().device_index, gl.info().device_count, gl.info().renderer, gl.info().version);
    SceneRenderer renderer(cluster_, channel_, scene);
    const uint64_t session = new_session_nonce();
    WireEndpoint wire = open_slave_endpoint(cluster_, channel_, key, session);
    spdlog::info("slave {}: ready to join {:.0f} ms after start (session {:016x})", channel_.name,
                 std::chrono::duration<double, std::milli>(Clock::now() - started).count(), session);
    const sockaddr_in master = master_report_address(cluster_);
    AsyncFrameWriter writer(options_.out_dir, options_.formats);
    SlaveCounters counters;
    const std::string log_name = "slave " + channel_.name;
    StatsWriter stats(options_.stats_file, log_name);
    // On every way out: the frames already rendered reach the disk before the process ends.
    auto stats_json = [&] {
        return nlohmann::json{{"role", "slave"},
                              {"channel", channel_.id},
                              {"session", fmt::format("{:016x}", session)},
                              {"master_session", fmt::format("{:016x}", wire.peer_session(kMasterSender))},
                              {"slave", counters.to_json()},
                              {"wire", wire.counters().to_json()}};
    };
    auto finish = [&](int code) {
        writer.flush();
        stats.write_now(stats_json());
        if (writer.failed() > 0) {
            spdlog::error("slave {}: {} frame(s) could not be written", channel_.name, writer.failed());
            return code == 0 ? 4 : code;
        }
        return code;
    };

    HelloMessage hello;
    hello.channel = static_cast<uint16_t>(channel_.id);
    hello.process_id = static_cast<uint32_t>(::getpid());
    std::optional<uint64_t> last_frame;
    std::optional<FrameReport> last_report;
    bool fresh_session = false;  // a master session was just established: any frame number may come next
    bool need_welcome = false;   // authentic packets from a master session we do not know: it restarted
    bool rendered_in_session = false;
    auto last_snapshot = Clock::now();
    auto last_hello = Clock::time_point{};
    std::deque<ReceivedMessage> pending;  // seen while catching up, handled next

    auto master_session = [&] { return wire.peer_session(kMasterSender); };
    auto send_hello = [&](uint64_t to) {
        hello.has_frame = last_frame.has_value();
        hello.last_frame = last_frame.value_or(0);
        wire.send(PacketType::Hello, hello.last_frame, encode_hello(hello), {master}, to);
        ++counters.hellos_sent;
        last_hello = Clock::now();
    };

    while (!stop_requested_) {
        const auto now = Clock::now();
        // Say hello until we are welcomed and snapshots flow, and whenever snapshots stop (we may
        // have been dropped). To session 0 — "whoever is master, welcome me" — while a master we do
        // not know is sending, and after a second without snapshots: a restarted master rejects
        // hellos addressed to its predecessor and sends nothing until channels join.
        const bool joining = master_session() == 0 || need_welcome || !rendered_in_session;
        const bool silent = now - last_snapshot > milliseconds(1000);
        if ((joining && now - last_hello > milliseconds(100)) ||
            (now - last_snapshot > milliseconds(500) && now - last_hello > milliseconds(500)))
            send_hello(need_welcome || silent ? 0 : master_session());
        if (now - last_snapshot > std::chrono::seconds(options_.idle_timeout_s)) {
            spdlog::error("slave {}: no snapshot for {} s; is the master running? exiting", channel_.name,
                          options_.idle_timeout_s);
            return finish(3);
        }
        stats.tick(stats_json);
        std::optional<ReceivedMessage> rm;
        if (!pending.empty()) {
            rm = std::move(pending.front());
            pending.pop_front();
        } else {
            rm = wire.receive(100);
        }
        if (!rm) continue;
        if (rm->message.sender != kMasterSender) continue;
        if (rm->opened) {
            ++counters.master_sessions;
            need_welcome = false;
            fresh_session = true;
            rendered_in_session = false;
            spdlog::info("slave {}: welcomed by master session {:016x}", channel_.name, master_session());
            send_hello(master_session());  // completes the handshake: the master now knows us
        } else if (!rm->verified) {
            if (!need_welcome)
                spdlog::info("slave {}: a master session {:016x} we do not know is sending: asking it for a welcome",
                             channel_.name, rm->message.session);
            need_welcome = true;
            continue;
        }
        if (!rm->verified) continue;
        const Message& m = rm->message;
        if (m.type == PacketType::Welcome) {
            if (!rm->opened && now - last_hello > milliseconds(100)) send_hello(master_session());
            continue;
        }
        if (m.type == PacketType::Quit) {
            // Confirm, and keep confirming for a moment in case our confirmation is lost.
            wire.send(PacketType::QuitAck, m.frame, encode_hello(hello), {master}, master_session());
            const auto linger_until = Clock::now() + milliseconds(300);
            while (Clock::now() < linger_until)
                if (auto q = wire.receive(50))
                    if (q->verified && q->message.sender == kMasterSender && q->message.type == PacketType::Quit)
                        wire.send(PacketType::QuitAck, m.frame, encode_hello(hello), {master}, master_session());
            spdlog::info("slave {}: master says quit after {} frames; stats {}", channel_.name,
                         counters.frames_rendered, stats_json().dump());
            return finish(0);
        }
        if (m.type != PacketType::Snapshot) continue;

        // Catching up after a stall: when newer snapshots are already queued, render only the newest.
        ReceivedMessage current = std::move(*rm);
        while (auto more = wire.receive(0)) {
            const Message& n = more->message;
            if (more->verified && !more->opened && n.sender == kMasterSender && n.type == PacketType::Snapshot &&
                n.session == current.message.session && n.frame > current.message.frame) {
                ++counters.skipped_snapshots;
                current = std::move(*more);
            } else {
                pending.push_back(std::move(*more));
            }
        }
        const Message& sm = current.message;
        const uint64_t received_ns = monotonic_ns();
        last_snapshot = Clock::now();
        const std::string hash = snapshot_hash(sm.payload);
        if (last_frame && sm.frame == *last_frame && last_report) {
            if (hash == last_report->snapshot_hash) {
                // The master resends while it waits: our report was lost (or it restarted). Repeat it.
                ++counters.resent_snapshots;
                rendered_in_session = true;
                fresh_session = false;
                wire.send(PacketType::FrameDone, sm.frame, encode_frame_report(*last_report), {master},
                          master_session());
                continue;
            }
            if (!fresh_session) {
                ++counters.late_snapshots;  // same frame, other content, same master: cannot be; ignore
                continue;
            }
            ++counters.rerendered;
        } else if (last_frame && sm.frame < *last_frame && !fresh_session) {
            ++counters.late_snapshots;  // reordered or a stale resend
            continue;
        }
        Snapshot snap;
        try {
            snap = decode_snapshot(sm.payload.data(), sm.payload.size());
            if (snap.frame != sm.frame) throw WireError("snapshot frame differs from its packet header");
            for (const auto& b : snap.bodies)
                if (b.id >= scene.bodies.size())
                    throw WireError("body id " + std::to_string(b.id) + " is not in the scene " + scene.file + " (" +
                                    std::to_string(scene.bodies.size()) +
                                    " bodies): do the master and this slave use the same scene file?");
        } catch (const WireError& e) {
            ++counters.malformed_snapshots;
            spdlog::warn("slave {}: malformed snapshot for frame {} dropped: {} ({} so far)", channel_.name, sm.frame,
                         e.what(), counters.malformed_snapshots);
            continue;
        }
        if (last_frame && snap.frame > *last_frame + 1) {
            counters.missed_frames += snap.frame - *last_frame - 1;
            spdlog::warn("slave {}: frames {}..{} never reached this channel ({} missed so far)", channel_.name,
                         *last_frame + 1, snap.frame - 1, counters.missed_frames);
        }
        const auto t0 = Clock::now();
        Image image = renderer.render(snap);
        const auto t1 = Clock::now();
        FrameMetadata meta;
        meta.channel_id = channel_.id;
        meta.channel_name = channel_.name;
        meta.frame = snap.frame;
        meta.sim_time_s = snap.sim_time_s;
        meta.snapshot_hash = hash;
        meta.renderer = gl.info().renderer;
        // Encoding overlaps the next frame's render; write_ms is the time spent waiting for room.
        const double wait_ms = writer.submit(std::move(image), std::move(meta), snap.settings.exposure);

        FrameReport rep;
        rep.channel = static_cast<uint16_t>(channel_.id);
        rep.frame = snap.frame;
        rep.snapshot_hash = hash;
        rep.render_ms = std::chrono::duration<float, std::milli>(t1 - t0).count();
        rep.write_ms = static_cast<float>(wait_ms);
        rep.packets_rejected = wire.counters().total_rejected() + counters.malformed_snapshots;
        rep.snapshots_missed = counters.missed_frames;
        rep.snapshot_received_ns = received_ns;
        rep.glare = renderer.glare_measurements();  // this frame's queries, for the next snapshot
        wire.send(PacketType::FrameDone, rep.frame, encode_frame_report(rep), {master}, master_session());
        last_report = rep;
        last_frame = snap.frame;
        fresh_session = false;
        rendered_in_session = true;
        ++counters.frames_rendered;
        spdlog::debug("slave {}: frame {} rendered in {:.1f} ms, queued for writing after {:.1f} ms", channel_.name,
                      rep.frame, rep.render_ms, rep.write_ms);
    }
    return finish(0);
}

}  // namespace cupola

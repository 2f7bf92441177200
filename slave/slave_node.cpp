#include "slave_node.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <optional>

#include "async_frame_writer.hpp"
#include "egl_context.hpp"
#include "image/frame_image.hpp"
#include "net/wire_endpoint.hpp"
#include "scene_renderer.hpp"
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
    const AuthKey key = load_key_file(cluster_.key_file);
    const SceneConfig scene = load_scene_config(cluster_.scene_file);
    EglContext gl(options_.egl_device);
    spdlog::info("slave {}: EGL {} (device {} of {}), {} / {}", channel_.name, gl.info().platform,
                 gl.info().device_index, gl.info().device_count, gl.info().renderer, gl.info().version);
    SceneRenderer renderer(cluster_, channel_, scene);
    WireEndpoint wire = open_slave_endpoint(cluster_, channel_, key);
    const sockaddr_in master = master_report_address(cluster_);
    AsyncFrameWriter writer(options_.out_dir, options_.formats);
    // On every way out: the frames already rendered reach the disk before the process ends.
    auto finish = [&](int code) {
        writer.flush();
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
    uint64_t missed = 0, malformed = 0, frames = 0;
    auto last_snapshot = Clock::now();
    auto last_hello = Clock::time_point{};
    const auto rejoin_after = milliseconds(cluster_.network.channel_timeout_ms);

    while (!stop_requested_) {
        const auto now = Clock::now();
        // Say hello until snapshots flow, and again whenever they stop (we may have been dropped).
        if ((!last_frame || now - last_snapshot > rejoin_after) && now - last_hello > milliseconds(250)) {
            hello.last_frame = last_frame.value_or(0);
            wire.send(PacketType::Hello, hello.last_frame, encode_hello(hello), {master});
            last_hello = now;
        }
        // While idle between frames, a heartbeat every second tells the master we are alive.
        if (last_frame && now - last_snapshot <= rejoin_after && now - last_snapshot > milliseconds(1000) &&
            now - last_hello > milliseconds(1000)) {
            wire.send(PacketType::Heartbeat, *last_frame, encode_hello(hello), {master});
            last_hello = now;
        }
        if (now - last_snapshot > std::chrono::seconds(options_.idle_timeout_s)) {
            spdlog::error("slave {}: no snapshot for {} s; is the master running? exiting", channel_.name,
                          options_.idle_timeout_s);
            return finish(3);
        }
        auto rm = wire.receive(100);
        if (!rm) continue;
        const Message& m = rm->message;
        if (m.sender != kMasterSender) continue;  // another slave's report seen through multicast loop
        if (m.type == PacketType::Quit) {
            spdlog::info("slave {}: master says quit after {} frames; {} snapshots missed, {} malformed; wire: {}",
                         channel_.name, frames, missed, malformed, wire.counters().summary());
            return finish(0);
        }
        if (m.type != PacketType::Snapshot) continue;
        const uint64_t received_ns = monotonic_ns();
        last_snapshot = Clock::now();
        if (last_frame && m.frame == *last_frame && last_report) {
            // The master resends while it waits: our report may have been lost. Repeat it.
            wire.send(PacketType::FrameDone, m.frame, encode_frame_report(*last_report), {master});
            continue;
        }
        if (last_frame && m.frame < *last_frame) continue;  // stale (reordered or late resend)
        Snapshot snap;
        try {
            snap = decode_snapshot(m.payload.data(), m.payload.size());
            if (snap.frame != m.frame) throw WireError("snapshot frame differs from its packet header");
            for (const auto& b : snap.bodies)
                if (b.id >= scene.bodies.size())
                    throw WireError("body id " + std::to_string(b.id) + " is not in the scene " + scene.file + " (" +
                                    std::to_string(scene.bodies.size()) +
                                    " bodies): do the master and this slave use the same scene file?");
        } catch (const WireError& e) {
            ++malformed;
            spdlog::warn("slave {}: malformed snapshot for frame {} dropped: {} ({} so far)", channel_.name, m.frame,
                         e.what(), malformed);
            continue;
        }
        if (last_frame && snap.frame > *last_frame + 1) {
            missed += snap.frame - *last_frame - 1;
            spdlog::warn("slave {}: frames {}..{} never arrived ({} missed so far)", channel_.name, *last_frame + 1,
                         snap.frame - 1, missed);
        }
        const std::string hash = snapshot_hash(m.payload);
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
        rep.packets_rejected = wire.counters().total_rejected() + malformed;
        rep.snapshots_missed = missed;
        rep.snapshot_received_ns = received_ns;
        rep.glare = renderer.glare_measurements();  // this frame's queries, for the next snapshot
        wire.send(PacketType::FrameDone, rep.frame, encode_frame_report(rep), {master});
        last_report = rep;
        last_frame = snap.frame;
        ++frames;
        spdlog::debug("slave {}: frame {} rendered in {:.1f} ms, queued for writing after {:.1f} ms", channel_.name, rep.frame,
                      rep.render_ms, rep.write_ms);
    }
    return finish(0);
}

}  // namespace cupola

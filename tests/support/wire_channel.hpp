#pragma once
// One channel played at the wire level by a test or benchmark process: it joins the master
// (hello / welcome / hello), answers every snapshot at once with its FrameDone, acknowledges quit,
// and keeps what it received (time, frame, camera) so the caller can wait for a change.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "config/cluster_config.hpp"
#include "net/key_file.hpp"
#include "net/wire_endpoint.hpp"
#include "util/monotonic_clock.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

namespace cupola::test {

struct Received {
    uint64_t ns = 0;  // monotonic_ns() at arrival
    uint64_t frame = 0;
    glm::dvec3 offset{0.0};  // camera - reference body (WireChannel's body index)
    glm::dquat orientation{1, 0, 0, 0};
};

// One channel at the wire level: joins, answers every snapshot at once, acknowledges quit.
class WireChannel {
public:
    // Plays cfg.channels[0]; `body` is the snapshot body the camera offsets are taken from.
    WireChannel(const ClusterConfig& cfg, const AuthKey& key, size_t body = 1)
        : cfg_(cfg), body_(body), ep_(open_slave_endpoint(cfg, cfg.channels[0], key, new_session_nonce())) {
        thread_ = std::thread([this] { loop(); });
    }
    ~WireChannel() {
        stop_ = true;
        thread_.join();
    }
    // Waits for the first snapshot received after `after_ns` that satisfies pred.
    template <class Pred>
    std::optional<Received> wait(uint64_t after_ns, Pred pred, std::chrono::milliseconds limit) {
        std::unique_lock lock(mutex_);
        std::optional<Received> hit;
        cv_.wait_for(lock, limit, [&] {
            for (size_t i = 1; i < got_.size(); ++i)
                if (got_[i].ns > after_ns && pred(got_[i - 1], got_[i])) {
                    hit = got_[i];
                    return true;
                }
            return false;
        });
        return hit;
    }
    std::vector<Received> received() {
        std::lock_guard lock(mutex_);
        return got_;
    }
    bool quit_seen() const { return quit_; }

private:
    void loop() {
        const auto master = master_report_address(cfg_);
        uint64_t master_session = 0;
        auto last_hello = std::chrono::steady_clock::now() - std::chrono::seconds(1);
        while (!stop_) {
            if (!master_session && std::chrono::steady_clock::now() - last_hello > std::chrono::milliseconds(100)) {
                HelloMessage h;
                h.channel = static_cast<uint16_t>(cfg_.channels[0].id);
                ep_.send(PacketType::Hello, 0, encode_hello(h), {master}, 0);
                last_hello = std::chrono::steady_clock::now();
            }
            auto m = ep_.receive(20);
            if (!m) continue;
            const uint64_t now = monotonic_ns();
            if (m->message.type == PacketType::Welcome && m->opened) {
                master_session = m->message.session;
                HelloMessage h;
                h.channel = static_cast<uint16_t>(cfg_.channels[0].id);
                ep_.send(PacketType::Hello, 0, encode_hello(h), {master}, master_session);
            } else if (m->message.type == PacketType::Snapshot && m->verified) {
                const Snapshot s = decode_snapshot(m->message.payload.data(), m->message.payload.size());
                FrameReport r;
                r.channel = static_cast<uint16_t>(cfg_.channels[0].id);
                r.frame = s.frame;
                r.snapshot_hash = snapshot_hash(m->message.payload);
                ep_.send(PacketType::FrameDone, s.frame, encode_frame_report(r), {master});
                std::lock_guard lock(mutex_);
                if (got_.empty() || got_.back().frame != s.frame)
                    got_.push_back(
                        {now, s.frame, s.camera_position_m - s.bodies.at(body_).position_m, s.camera_orientation});
                cv_.notify_all();
            } else if (m->message.type == PacketType::Quit && m->verified) {
                ep_.send(PacketType::QuitAck, m->message.frame, {}, {master});
                quit_ = true;
            }
        }
    }

    const ClusterConfig& cfg_;
    size_t body_;
    WireEndpoint ep_;
    std::mutex mutex_;
    std::condition_variable cv_;
    std::vector<Received> got_;
    std::atomic<bool> stop_{false}, quit_{false};
    std::thread thread_;
};

}  // namespace cupola::test

#pragma once
// One channel played at the wire level by a test or benchmark process, through the slave's own
// session code (session/slave_session.hpp): it joins the master (hello / welcome / hello), answers
// every new snapshot at once with its FrameDone, acknowledges quit, and keeps what it received
// (time, frame, camera) so the caller can wait for a change.
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
#include "support/wire_handshake.hpp"
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
    // The channel's side of the protocol is a SlaveSession (the slave process's own), with
    // "render" meaning: note what arrived and report at once. It never gives up for idleness.
    void loop() {
        using Clock = std::chrono::steady_clock;
        SlaveSession session = slave_session_for(cfg_.channels[0], std::chrono::hours(24));
        while (!stop_) {
            send_all(ep_, cfg_, session.tick(Clock::now()));
            if (auto m = receive_until(ep_, Clock::now() + std::chrono::milliseconds(20)))
                session.receive(std::move(*m));
            const uint64_t now = monotonic_ns();
            SlaveActions a = session.step(Clock::now());
            send_all(ep_, cfg_, a);
            if (session.quitting()) quit_ = true;
            if (!a.render) continue;
            const Snapshot& s = a.render->snapshot;
            {
                std::lock_guard lock(mutex_);
                got_.push_back(
                    {now, s.frame, s.camera_position_m - s.bodies.at(body_).position_m, s.camera_orientation});
            }
            cv_.notify_all();
            send_all(ep_, cfg_, session.rendered(FrameReport{}, ep_.counters().total_rejected()));
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

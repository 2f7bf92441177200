#include "tracking/dtrack_receiver.hpp"

#include <spdlog/spdlog.h>

#include <string_view>

#include "tracking/dtrack_packet.hpp"
#include "tracking/tracker_mounting.hpp"
#include "util/monotonic_clock.hpp"

namespace cupola {

namespace {
constexpr uint64_t kLoggedBadPackets = 10;  // then every hundredth
}

DtrackReceiver::DtrackReceiver(const HeadTrackingConfig& config) : config_(config) {
    socket_.set_reuse_address();
    socket_.bind(make_address(config.address, config.port));
    spdlog::info("master: head tracking from DTrack2 on {}:{}, body {}", config.address, port(), config.body);
}

void DtrackReceiver::drain(HeadTracker& tracker) {
    while (auto d = socket_.receive(0)) take(*d, tracker);
}

void DtrackReceiver::take(const UdpSocket::Datagram& d, HeadTracker& tracker) {
    HeadTrackerCounters& c = tracker.counters();
    ++c.packets;
    const uint64_t now = monotonic_ns();
    const uint64_t arrival_ns = now > d.queued_ns ? now - d.queued_ns : now;
    try {
        const DtrackPacket p =
            parse_dtrack_packet(std::string_view(reinterpret_cast<const char*>(d.data.data()), d.data.size()));
        const DtrackBody* head = find_dtrack_body(p, config_.body);
        if (!head) {
            ++c.without_body;
            return;
        }
        tracker.add_sample(head_pose_from_dtrack(*head, config_.mounting), arrival_ns);
    } catch (const DtrackError& e) {
        ++c.bad_packets;
        if (c.bad_packets <= kLoggedBadPackets || c.bad_packets % 100 == 0)
            spdlog::warn("master: tracker datagram {} from {} refused ({} so far): {}", c.packets, to_string(d.from),
                         c.bad_packets, e.what());
    }
}

}  // namespace cupola

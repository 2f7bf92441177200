#pragma once
// The master's socket for an A.R.T. DTrack2 tracker (room.tracking.source "dtrack"): every datagram
// waiting is read once per frame, parsed (tracking/dtrack_packet.hpp), and the head's body handed
// to the HeadTracker with its arrival time. A datagram that is not DTrack2 output is refused,
// counted and logged (the first ten, then every hundredth) and changes nothing.
#include <cstdint>

#include "net/udp_socket.hpp"
#include "tracking/head_tracker.hpp"

namespace cupola {

class DtrackReceiver {
public:
    // Binds config.address:config.port; throws std::system_error naming the address.
    explicit DtrackReceiver(const HeadTrackingConfig& config);

    // Reads every datagram waiting now (none: returns at once) into the tracker.
    void drain(HeadTracker& tracker);

    uint16_t port() const { return socket_.local_port(); }

private:
    void take(const UdpSocket::Datagram& d, HeadTracker& tracker);

    HeadTrackingConfig config_;
    UdpSocket socket_;
};

}  // namespace cupola

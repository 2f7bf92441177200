#pragma once
// A thin RAII wrapper over an IPv4 UDP socket: bind, multicast/broadcast options, send, and
// receive with a timeout. Errors throw std::system_error naming the call and the address.
#include <netinet/in.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cupola {

sockaddr_in make_address(const std::string& ipv4, uint16_t port);
sockaddr_in parse_host_port(const std::string& host_port);  // "127.0.0.1:47610"
std::string to_string(const sockaddr_in& a);

class UdpSocket {
public:
    UdpSocket();
    ~UdpSocket();
    UdpSocket(UdpSocket&& other) noexcept;
    UdpSocket& operator=(UdpSocket&& other) noexcept;
    UdpSocket(const UdpSocket&) = delete;
    UdpSocket& operator=(const UdpSocket&) = delete;

    void set_reuse_address();
    void bind(const sockaddr_in& address);
    void join_multicast(const std::string& group, const std::string& interface_address);
    void set_multicast_sender(const std::string& interface_address);  // IF + loopback on + ttl 1
    void enable_broadcast();
    void set_receive_buffer(int bytes);

    // false when the network refused the datagram for now (link down, no route, full queue,
    // firewall): lost like any datagram. Throws for errors of the program (bad socket, too large).
    bool send_to(const sockaddr_in& to, const uint8_t* data, size_t size);

    struct Datagram {
        std::vector<uint8_t> data;
        sockaddr_in from{};
        // How long it waited in the socket's queue before this read (from the kernel's receive
        // timestamp); 0 when the kernel gave none. A process busy elsewhere (a slave rendering)
        // reads late, and what arrived together must still count as arriving together. Linux
        // turns its stamps on a moment after the first socket asks; what arrives before then is
        // stamped at the read (queued_ns about 0).
        uint64_t queued_ns = 0;
    };
    // Waits up to timeout_ms (0: poll); nothing when no datagram arrived in time.
    std::optional<Datagram> receive(int timeout_ms);

    uint16_t local_port() const;
    int fd() const { return fd_; }

private:
    int fd_ = -1;
};

}  // namespace cupola

#include "net/udp_socket.hpp"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <system_error>

namespace cupola {

namespace {
[[noreturn]] void fail(const std::string& what) { throw std::system_error(errno, std::generic_category(), what); }
}  // namespace

sockaddr_in make_address(const std::string& ipv4, uint16_t port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    if (inet_pton(AF_INET, ipv4.c_str(), &a.sin_addr) != 1)
        throw std::invalid_argument("\"" + ipv4 + "\" is not an IPv4 address");
    return a;
}

sockaddr_in parse_host_port(const std::string& s) {
    auto colon = s.rfind(':');
    if (colon == std::string::npos) throw std::invalid_argument("\"" + s + "\" is not of the form IPv4:port");
    int port = 0;
    try {
        port = std::stoi(s.substr(colon + 1));
    } catch (const std::exception&) {
        throw std::invalid_argument("\"" + s + "\" has no valid port");
    }
    if (port < 1 || port > 65535) throw std::invalid_argument("\"" + s + "\" has no valid port");
    return make_address(s.substr(0, colon), static_cast<uint16_t>(port));
}

std::string to_string(const sockaddr_in& a) {
    char buf[INET_ADDRSTRLEN] = {};
    inet_ntop(AF_INET, &a.sin_addr, buf, sizeof buf);
    return std::string(buf) + ":" + std::to_string(ntohs(a.sin_port));
}

namespace {

// The time since the kernel's receive timestamp (SCM_TIMESTAMPNS, the real-time clock) of a
// received message; 0 without one, or when the clock stepped back past it.
uint64_t queued_since_arrival(msghdr& m) {
    for (cmsghdr* c = CMSG_FIRSTHDR(&m); c; c = CMSG_NXTHDR(&m, c)) {
        if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SCM_TIMESTAMPNS) continue;
        timespec arrived{}, now{};
        std::memcpy(&arrived, CMSG_DATA(c), sizeof arrived);
        clock_gettime(CLOCK_REALTIME, &now);
        const int64_t ns = (static_cast<int64_t>(now.tv_sec) - arrived.tv_sec) * 1'000'000'000LL +
                           (static_cast<int64_t>(now.tv_nsec) - arrived.tv_nsec);
        return ns > 0 ? static_cast<uint64_t>(ns) : 0;
    }
    return 0;
}

}  // namespace

UdpSocket::UdpSocket() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) fail("socket(AF_INET, SOCK_DGRAM)");
    const int on = 1;  // the kernel's receive timestamps (Datagram::queued_ns); without them, 0
    ::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
}

UdpSocket::~UdpSocket() {
    if (fd_ >= 0) ::close(fd_);
}

UdpSocket::UdpSocket(UdpSocket&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }

UdpSocket& UdpSocket::operator=(UdpSocket&& o) noexcept {
    if (this != &o) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = o.fd_;
        o.fd_ = -1;
    }
    return *this;
}

void UdpSocket::set_reuse_address() {
    int one = 1;
    if (setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0) fail("setsockopt(SO_REUSEADDR)");
}

void UdpSocket::bind(const sockaddr_in& a) {
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) fail("bind(" + to_string(a) + ")");
}

void UdpSocket::join_multicast(const std::string& group, const std::string& iface) {
    ip_mreq m{};
    if (inet_pton(AF_INET, group.c_str(), &m.imr_multiaddr) != 1 ||
        inet_pton(AF_INET, iface.c_str(), &m.imr_interface) != 1)
        throw std::invalid_argument("bad multicast group or interface: " + group + " / " + iface);
    if (setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &m, sizeof m) != 0)
        fail("IP_ADD_MEMBERSHIP " + group + " on " + iface);
}

void UdpSocket::set_multicast_sender(const std::string& iface) {
    in_addr a{};
    if (inet_pton(AF_INET, iface.c_str(), &a) != 1) throw std::invalid_argument("bad interface " + iface);
    if (setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_IF, &a, sizeof a) != 0) fail("IP_MULTICAST_IF " + iface);
    unsigned char loop = 1, ttl = 1;
    if (setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0) fail("IP_MULTICAST_LOOP");
    if (setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) != 0) fail("IP_MULTICAST_TTL");
}

void UdpSocket::enable_broadcast() {
    int one = 1;
    if (setsockopt(fd_, SOL_SOCKET, SO_BROADCAST, &one, sizeof one) != 0) fail("setsockopt(SO_BROADCAST)");
}

void UdpSocket::set_receive_buffer(int bytes) {
    if (setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes) != 0) fail("setsockopt(SO_RCVBUF)");
}

bool UdpSocket::send_to(const sockaddr_in& to, const uint8_t* data, size_t size) {
    for (;;) {
        ssize_t n = ::sendto(fd_, data, size, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
        if (n >= 0) return true;
        if (errno == EINTR) continue;
        // The network, not the program: a peer that is gone (ECONNREFUSED from an earlier ICMP), a
        // full queue, a link that is down (no route while it is), a firewall. The datagram is lost
        // like any other; the protocol recovers. The caller counts it.
        if (errno == ECONNREFUSED || errno == ENOBUFS || errno == EAGAIN || errno == ENETUNREACH ||
            errno == EHOSTUNREACH || errno == ENETDOWN || errno == EHOSTDOWN || errno == EPERM)
            return false;
        fail("sendto(" + to_string(to) + ")");
    }
}

std::optional<UdpSocket::Datagram> UdpSocket::receive(int timeout_ms) {
    pollfd p{fd_, POLLIN, 0};
    int r = ::poll(&p, 1, timeout_ms);
    if (r < 0) {
        if (errno == EINTR) return std::nullopt;
        fail("poll");
    }
    if (r == 0) return std::nullopt;
    Datagram d;
    d.data.resize(65536);
    iovec iov{d.data.data(), d.data.size()};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec))];
    msghdr m{};
    m.msg_name = &d.from;
    m.msg_namelen = sizeof d.from;
    m.msg_iov = &iov;
    m.msg_iovlen = 1;
    m.msg_control = control;
    m.msg_controllen = sizeof control;
    ssize_t n = ::recvmsg(fd_, &m, 0);
    if (n < 0) {
        if (errno == EINTR || errno == EAGAIN || errno == ECONNREFUSED) return std::nullopt;
        fail("recvmsg");
    }
    d.data.resize(static_cast<size_t>(n));
    d.queued_ns = queued_since_arrival(m);
    return d;
}

uint16_t UdpSocket::local_port() const {
    sockaddr_in a{};
    socklen_t len = sizeof a;
    if (getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0) fail("getsockname");
    return ntohs(a.sin_port);
}

}  // namespace cupola

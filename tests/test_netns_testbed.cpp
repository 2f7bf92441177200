// Self-test of the network-namespace test bed (tests/support/netns_testbed.hpp): unicast between
// every pair of hosts, multicast to every other host, programs started inside a host, random loss
// with an exact drop counter, link down/up, and cleanup (normal, on exceptions, stale leftovers).
// Skipped (with the reason) where the machine cannot create namespaces (not root, no nft, ...).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/netns_testbed.hpp"
#include "support/test_support.hpp"
#include "util/child_process.hpp"

namespace cupola::test {
namespace {

using namespace std::chrono_literals;

#define SKIP_IF_NO_NETNS()                                          \
    do {                                                            \
        const std::string why = NetnsTestbed::unavailable_reason(); \
        if (!why.empty()) GTEST_SKIP() << why;                      \
    } while (0)

// A UDP socket made inside one host of the test bed, closed on destruction.
class Udp {
public:
    Udp(const NetnsTestbed& bed, const std::string& host) : fd_(bed.open_socket(host, SOCK_DGRAM)) {}
    ~Udp() { ::close(fd_); }
    Udp(const Udp&) = delete;
    Udp& operator=(const Udp&) = delete;
    int fd() const { return fd_; }

    void bind_port(int port) {
        const int one = 1;
        ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_port = htons(static_cast<uint16_t>(port));
        a.sin_addr.s_addr = htonl(INADDR_ANY);
        if (::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0)
            throw std::runtime_error("bind " + std::to_string(port) + " failed");
    }
    void join(const std::string& group) {
        ip_mreq m{};
        inet_pton(AF_INET, group.c_str(), &m.imr_multiaddr);
        m.imr_interface.s_addr = htonl(INADDR_ANY);
        if (::setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &m, sizeof m) != 0)
            throw std::runtime_error("join " + group + " failed");
    }
    void send_to(const std::string& address, int port, const std::string& payload) {
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_port = htons(static_cast<uint16_t>(port));
        inet_pton(AF_INET, address.c_str(), &a.sin_addr);
        if (::sendto(fd_, payload.data(), payload.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a) !=
            static_cast<ssize_t>(payload.size()))
            throw std::runtime_error("sendto " + address + " failed");
    }
    struct Datagram {
        std::string payload;
        std::string from;  // sender's IPv4 address
    };
    // The next datagram, or nothing when none comes within the timeout.
    std::optional<Datagram> receive(std::chrono::milliseconds timeout) {
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return std::nullopt;
        char buf[2048];
        sockaddr_in from{};
        socklen_t len = sizeof from;
        const ssize_t n = ::recvfrom(fd_, buf, sizeof buf, 0, reinterpret_cast<sockaddr*>(&from), &len);
        if (n < 0) return std::nullopt;
        char addr[INET_ADDRSTRLEN] = {};
        inet_ntop(AF_INET, &from.sin_addr, addr, sizeof addr);
        return Datagram{std::string(buf, static_cast<size_t>(n)), addr};
    }

private:
    int fd_;
};

std::set<std::string> netns_names() {
    std::set<std::string> out;
    auto [rc, text] = run_shell("ip netns list 2>/dev/null");
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(pos, end - pos);
        const std::string name = line.substr(0, line.find(' '));
        if (!name.empty()) out.insert(name);
        pos = end + 1;
    }
    return out;
}

std::set<std::string> root_interfaces() {
    std::set<std::string> out;
    auto [rc, text] = run_shell("ls /sys/class/net");
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find_first_of(" \n", pos);
        if (end == std::string::npos) end = text.size();
        if (end > pos) out.insert(text.substr(pos, end - pos));
        pos = end + 1;
    }
    return out;
}

TEST(NetnsTestbed, HostsLayoutAndIsolation) {
    SKIP_IF_NO_NETNS();
    const auto root_before = root_interfaces();
    const auto root_addrs_before = run_shell("ip -o addr show").second;
    const auto t0 = std::chrono::steady_clock::now();
    NetnsTestbed bed("layout", {"master", "s1", "s2"});
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0);
    std::cout << "[          ] creating a 3-host test bed took " << ms.count() << " ms\n";

    EXPECT_EQ(bed.host("master").address, "10.77.0.2");
    EXPECT_EQ(bed.host("s1").address, "10.77.0.3");
    EXPECT_EQ(bed.host("s2").address, "10.77.0.4");
    EXPECT_NE(bed.host("s1").ns, bed.host("s2").ns);
    EXPECT_NE(bed.host("s1").ns.find("cpl" + std::to_string(::getpid()) + "-layout"), std::string::npos);
    try {
        bed.host("nobody");
        ADD_FAILURE() << "host('nobody') did not throw";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("nobody"), std::string::npos) << e.what();
    }

    // Nothing was added to the root namespace.
    EXPECT_EQ(root_interfaces(), root_before);
    EXPECT_EQ(run_shell("ip -o addr show").second, root_addrs_before);

    // Inside a host: exactly lo and eth0, eth0 carrying the host's address, and the multicast route.
    auto [rc, links] = bed.run("s1", "ls /sys/class/net | sort | tr '\\n' ' '");
    EXPECT_EQ(rc, 0);
    EXPECT_EQ(links, "eth0 lo ");
    auto [rc2, addr] = bed.run("s1", "ip -4 -o addr show dev eth0");
    EXPECT_EQ(rc2, 0);
    EXPECT_NE(addr.find("10.77.0.3/24"), std::string::npos) << addr;
    EXPECT_NE(bed.run("s1", "ip route show 224.0.0.0/4").second.find("dev eth0"), std::string::npos);
    EXPECT_EQ(bed.run("s1", "exit 3").first, 3);
    // The switch holds the bridge with snooping off.
    auto [rc3, br] = run_shell("ip -n " + bed.switch_namespace() + " -d link show br0");
    EXPECT_EQ(rc3, 0);
    EXPECT_NE(br.find("mcast_snooping 0"), std::string::npos) << br;
}

TEST(NetnsTestbed, EveryPairExchangesUdpAndMulticastReachesAll) {
    SKIP_IF_NO_NETNS();
    const std::vector<std::string> names = {"a", "b", "c"};
    NetnsTestbed bed("pairs", names);
    constexpr int kPort = 40000;
    std::vector<std::unique_ptr<Udp>> socks;
    for (const auto& n : names) {
        socks.push_back(std::make_unique<Udp>(bed, n));
        socks.back()->bind_port(kPort);
    }
    for (size_t i = 0; i < names.size(); ++i) {
        for (size_t j = 0; j < names.size(); ++j) {
            if (i == j) continue;
            const std::string payload = "from " + names[i] + " to " + names[j];
            socks[i]->send_to(bed.host(names[j]).address, kPort, payload);
            auto got = socks[j]->receive(2000ms);
            ASSERT_TRUE(got) << payload << " did not arrive";
            EXPECT_EQ(got->payload, payload);
            EXPECT_EQ(got->from, bed.host(names[i]).address);
        }
    }
    // Nothing else is pending anywhere.
    for (auto& s : socks) EXPECT_FALSE(s->receive(50ms));

    // Multicast from a reaches b and c.
    constexpr int kGroupPort = 40100;
    Udp rb(bed, "b"), rc(bed, "c"), tx(bed, "a");
    rb.bind_port(kGroupPort);
    rb.join("239.255.90.1");
    rc.bind_port(kGroupPort);
    rc.join("239.255.90.1");
    const unsigned char ttl = 1;
    ::setsockopt(tx.fd(), IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
    tx.send_to("239.255.90.1", kGroupPort, "hello group");
    for (Udp* r : {&rb, &rc}) {
        auto got = r->receive(2000ms);
        ASSERT_TRUE(got) << "multicast did not arrive";
        EXPECT_EQ(got->payload, "hello group");
        EXPECT_EQ(got->from, bed.host("a").address);
    }

    // A real program started inside host a (via exec_prefix + ChildProcess) reaches host b.
    Udp rx(bed, "b");
    rx.bind_port(40200);
    std::vector<std::string> argv = bed.exec_prefix("a");
    ASSERT_EQ(argv.size(), 4u);
    EXPECT_EQ(argv[1], "netns");
    EXPECT_EQ(argv[3], bed.host("a").ns);
    argv.insert(argv.end(), {"bash", "-c", "printf from-child > /dev/udp/" + bed.host("b").address + "/40200"});
    cupola::ChildProcess child(argv);
    ASSERT_EQ(child.wait_for(5000ms), std::optional<int>(0));
    auto got = rx.receive(2000ms);
    ASSERT_TRUE(got) << "the datagram of the child in host a did not arrive";
    EXPECT_EQ(got->payload, "from-child");
    EXPECT_EQ(got->from, bed.host("a").address);
}

// Sends `count` datagrams from tx to rx's port, paced so that nothing but the loss rule drops any
// (the kernel's per-CPU backlog holds ~1000 packets); returns how many arrived.
int send_and_count(Udp& tx, Udp& rx, const std::string& address, int port, int count) {
    int received = 0;
    auto drain = [&](std::chrono::milliseconds wait) {
        while (rx.receive(wait)) ++received;
    };
    for (int i = 0; i < count; ++i) {
        tx.send_to(address, port, "datagram " + std::to_string(i));
        if (i % 50 == 49) drain(0ms);
    }
    drain(100ms);  // datagrams cross the namespaces in microseconds
    return received;
}

TEST(NetnsTestbed, RandomLossWithExactCounter) {
    SKIP_IF_NO_NETNS();
    NetnsTestbed bed("loss", {"tx", "rx"});
    constexpr int kPort = 40300;
    Udp tx(bed, "tx"), rx(bed, "rx"), rx_other(bed, "rx");
    rx.bind_port(kPort);
    rx_other.bind_port(kPort + 10);
    const int big = 8 << 20;
    ::setsockopt(rx.fd(), SOL_SOCKET, SO_RCVBUFFORCE, &big, sizeof big);
    const std::string to = bed.host("rx").address;

    EXPECT_EQ(bed.dropped_packets("rx"), 0u);
    bed.set_loss("rx", 20.0, kPort, kPort + 5);
    constexpr int kSent = 2000;
    const int received = send_and_count(tx, rx, to, kPort, kSent);
    const double fraction = static_cast<double>(received) / kSent;
    std::cout << "[          ] 20 % loss: " << received << " of " << kSent << " arrived\n";
    EXPECT_GE(fraction, 0.76) << received << " of " << kSent;
    EXPECT_LE(fraction, 0.84) << received << " of " << kSent;
    EXPECT_EQ(bed.dropped_packets("rx"), static_cast<uint64_t>(kSent - received));
    EXPECT_EQ(bed.dropped_packets("tx"), 0u);

    // Ports outside the range are untouched.
    EXPECT_EQ(send_and_count(tx, rx_other, to, kPort + 10, 200), 200);
    EXPECT_EQ(bed.dropped_packets("rx"), static_cast<uint64_t>(kSent - received));

    // A new rule replaces the old one (its counter starts again); 100 % drops everything.
    bed.set_loss("rx", 100.0, kPort, kPort);
    EXPECT_EQ(bed.dropped_packets("rx"), 0u);
    EXPECT_EQ(send_and_count(tx, rx, to, kPort, 100), 0);
    EXPECT_EQ(bed.dropped_packets("rx"), 100u);

    // 0 % removes the rule.
    bed.set_loss("rx", 0.0, kPort, kPort);
    EXPECT_EQ(bed.dropped_packets("rx"), 0u);
    EXPECT_EQ(send_and_count(tx, rx, to, kPort, 100), 100);
    EXPECT_EQ(bed.run("rx", "nft list tables").second, "");

    EXPECT_THROW(bed.set_loss("rx", 120.0, kPort, kPort), std::invalid_argument);
    EXPECT_THROW(bed.set_loss("rx", 10.0, 5000, 4000), std::invalid_argument);
}

TEST(NetnsTestbed, LinkDownAndUp) {
    SKIP_IF_NO_NETNS();
    NetnsTestbed bed("link", {"a", "b"});
    constexpr int kPort = 40400;
    Udp tx(bed, "a"), rx(bed, "b");
    rx.bind_port(kPort);
    const std::string to = bed.host("b").address;

    tx.send_to(to, kPort, "before");
    auto got = rx.receive(2000ms);
    ASSERT_TRUE(got);
    EXPECT_EQ(got->payload, "before");

    bed.link_down("b");
    EXPECT_NE(bed.run("b", "ip link show eth0").second.find("state DOWN"), std::string::npos);
    for (int i = 0; i < 5; ++i) tx.send_to(to, kPort, "while-down");
    got = rx.receive(400ms);
    EXPECT_FALSE(got) << "a datagram arrived while the link was down: " << got->payload;

    bed.link_up("b");
    EXPECT_NE(bed.run("b", "ip route show 224.0.0.0/4").second.find("dev eth0"), std::string::npos);
    // The bridge port and carrier come back quickly; retry for a while.
    const auto deadline = std::chrono::steady_clock::now() + 3s;
    std::optional<Udp::Datagram> after;
    while (!after && std::chrono::steady_clock::now() < deadline) {
        tx.send_to(to, kPort, "after");
        after = rx.receive(50ms);
    }
    ASSERT_TRUE(after) << "no datagram arrived after link_up";
    EXPECT_EQ(after->payload, "after");  // the ones sent while down were really dropped
}

TEST(NetnsTestbed, DestructorDeletesEveryNamespace) {
    SKIP_IF_NO_NETNS();
    std::vector<std::string> made;
    {
        NetnsTestbed bed("gone", {"m", "s1", "s2"});
        made = bed.namespaces();
        ASSERT_EQ(made.size(), 4u);
        const auto now = netns_names();
        for (const auto& ns : made) EXPECT_TRUE(now.count(ns)) << ns << " missing while the test bed lives";
    }
    const auto after = netns_names();
    for (const auto& ns : made) EXPECT_FALSE(after.count(ns)) << ns << " left behind";
}

TEST(NetnsTestbed, CleansUpWhenLeftByAnException) {
    SKIP_IF_NO_NETNS();
    std::vector<std::string> made;
    auto body = [&] {
        NetnsTestbed bed("throw", {"x", "y"});
        made = bed.namespaces();
        throw std::runtime_error("assertion fired");
    };
    EXPECT_THROW(body(), std::runtime_error);
    ASSERT_EQ(made.size(), 3u);
    const auto after = netns_names();
    for (const auto& ns : made) EXPECT_FALSE(after.count(ns)) << ns << " left behind";
}

TEST(NetnsTestbed, FailedConstructionCleansUpAndNamesTheCommand) {
    SKIP_IF_NO_NETNS();
    // A host name too long for a namespace name makes `ip netns add` fail after the switch and the
    // first host were made.
    const std::string prefix = "cpl" + std::to_string(::getpid()) + "-midfail";
    try {
        NetnsTestbed bed("midfail", {"ok", std::string(300, 'z')});
        ADD_FAILURE() << "construction did not fail";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("netns add"), std::string::npos) << e.what();
    }
    for (const auto& ns : netns_names()) EXPECT_NE(ns.rfind(prefix, 0), 0u) << ns << " left behind";

    EXPECT_THROW(NetnsTestbed("dup", {"a", "a"}), std::invalid_argument);
    EXPECT_THROW(NetnsTestbed("bad", {"a b"}), std::invalid_argument);
}

TEST(NetnsTestbed, RemovesStaleNamespacesOfDeadProcesses) {
    SKIP_IF_NO_NETNS();
    // A pid that no longer exists: a child that has exited and been reaped.
    cupola::ChildProcess child({"/bin/true"});
    ASSERT_EQ(child.wait_for(5000ms), std::optional<int>(0));
    const pid_t dead = child.pid();
    ASSERT_FALSE(std::filesystem::exists("/proc/" + std::to_string(dead)));
    const std::string stale = "cpl" + std::to_string(dead) + "-stale0-x";
    // A test process running beside this one may sweep it away at any moment (even half made, so
    // that `ip netns add` fails): retry.
    bool made = false;
    for (int i = 0; i < 10 && !made; ++i) made = run_shell("ip netns add " + stale + " 2>&1").first == 0;
    ASSERT_TRUE(made) << "cannot create " << stale;
    // One named after another live process (as if a concurrent test made it) must survive, and so
    // must one of this process.
    cupola::ChildProcess alive({"/bin/sleep", "30"});
    const std::string other_live = "cpl" + std::to_string(alive.pid()) + "-alive0-x";
    ASSERT_EQ(run_shell("ip netns add " + other_live).first, 0);
    NetnsTestbed mine("live", {"h"});
    NetnsTestbed other("stale", {"h"});  // constructing runs the stale sweep
    const auto now = netns_names();
    EXPECT_FALSE(now.count(stale)) << "stale namespace not removed";
    EXPECT_TRUE(now.count(other_live)) << "the namespace of a live process was removed";
    EXPECT_TRUE(now.count(mine.host("h").ns)) << "a live test bed's namespace was removed";
    run_shell("ip netns del " + stale + " 2>/dev/null");
    run_shell("ip netns del " + other_live + " 2>/dev/null");
}

}  // namespace
}  // namespace cupola::test

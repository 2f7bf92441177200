#pragma once
// A test bed of Linux network namespaces for real multi-host cluster tests on one machine.
//
// Layout: one "switch" namespace holding a Linux bridge br0 (multicast snooping off, so multicast
// floods to every port, STP off), and one namespace per host joined to the bridge by a veth pair.
// Inside a host namespace the interface is "eth0", addressed 10.77.0.(i+2)/24 in the order the hosts
// were given, with loopback up and a route 224.0.0.0/4 dev eth0 so multicast goes out on it.
// Nothing is added to the root namespace: the veth pairs are created directly inside the
// namespaces, so two test beds (even in two processes) never collide.
//
// Namespace names are "cpl<pid>-<tag><n>-<host>" (and "cpl<pid>-<tag><n>--sw" for the switch),
// where n is a per-process counter. Construction also deletes stale "cpl<pid>-..." namespaces whose
// process no longer exists (left by a test that was killed).
//
// Needs root (CAP_SYS_ADMIN + CAP_NET_ADMIN), `ip` (iproute2) and `nft` (nftables); tests call
// GTEST_SKIP() << NetnsTestbed::unavailable_reason() when it is not empty.
//
// IMPORTANT: stop every process you started inside a namespace (ChildProcess etc.) BEFORE the
// test bed is destroyed. Deleting a namespace only removes its name; a namespace that still holds a
// running process lives on (with its interfaces) until that process exits. Declare the test bed
// before the ChildProcess objects so that they are destroyed (SIGKILLed) first.
//
// Sockets: open_socket() creates a socket inside a host's namespace from the calling process
// (a socket stays in the namespace it was created in), so a test can talk as "host X" without
// starting any program.
#include <sys/socket.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace cupola::test {

struct NetnsHost {
    std::string name;     // e.g. "master", "s1", "relay", "attacker"
    std::string ns;       // the network namespace's name
    std::string address;  // IPv4 of its interface, e.g. "10.77.0.2"
};

class NetnsTestbed {
public:
    // Why this machine cannot host the test bed ("" when it can): not root, `ip` or `nft` missing,
    // or creating a namespace / veth pair / bridge / nft table in it fails. Probed once per process.
    static std::string unavailable_reason();

    // Builds the test bed (see the top of this file). tag: a short label for the namespace names
    // (characters other than [A-Za-z0-9_] are dropped, at most 12 kept). host_names: unique, non-empty,
    // [A-Za-z0-9_-] (std::invalid_argument otherwise), at most 200 hosts; the namespace name must stay
    // within 255 characters. Throws std::runtime_error naming the failing command, having deleted
    // whatever it had made.
    NetnsTestbed(const std::string& tag, const std::vector<std::string>& host_names);
    ~NetnsTestbed();  // deletes every namespace it made (this removes the veths too), never throws
    NetnsTestbed(const NetnsTestbed&) = delete;
    NetnsTestbed& operator=(const NetnsTestbed&) = delete;

    const NetnsHost& host(const std::string& name) const;  // throws naming the host
    const std::vector<NetnsHost>& hosts() const { return hosts_; }
    // Every namespace this test bed made (the hosts' and the switch's).
    std::vector<std::string> namespaces() const;
    const std::string& switch_namespace() const { return switch_ns_; }

    // argv prefix that runs a program inside the host's namespace: {<ip>,"netns","exec",ns}, where
    // <ip> is the absolute path of the `ip` program (cupola::ChildProcess does not search PATH).
    // The program after the prefix is looked up in PATH by `ip netns exec`.
    std::vector<std::string> exec_prefix(const std::string& host) const;

    // Drops `percent` % of the incoming UDP datagrams to destination ports [port_lo, port_hi] on that
    // host at random (nftables `numgen random mod 1000 < percent*10 drop`, with a counter, in table
    // `inet cupola_loss`), replacing any earlier loss rule on that host (its counter restarts at 0).
    // percent 0 removes the rule. Throws on bad arguments or when nft fails.
    void set_loss(const std::string& host, double percent, int port_lo, int port_hi);
    // Packets dropped so far by that host's current loss rule (parsed from the nft counter); 0 when
    // the host has no loss rule.
    uint64_t dropped_packets(const std::string& host) const;

    void link_down(const std::string& host);  // ip link set eth0 down inside the host
    void link_up(const std::string& host);    // and up again (re-adds the multicast route)

    // Runs a shell command line (sh -c) inside the host's namespace; returns {exit status, stdout}
    // (status -1 when it did not exit normally). stderr is not captured.
    std::pair<int, std::string> run(const std::string& host, const std::string& command) const;

    // A new socket (socket(AF_INET, type, 0) by default) created inside the host's namespace; the
    // caller owns (closes) the descriptor. Throws when it cannot be made.
    int open_socket(const std::string& host, int type, int domain = AF_INET) const;

private:
    void destroy() noexcept;
    void must(const std::string& command) const;  // runs it in the root namespace; throws on failure

    std::vector<NetnsHost> hosts_;
    std::string switch_ns_;
    std::vector<std::string> created_;  // namespaces to delete (added before each is made)
};

// Deletes "cpl<pid>-..." namespaces whose process <pid> no longer exists; returns their names.
// The constructor calls it; exposed for tests.
std::vector<std::string> remove_stale_netns();

}  // namespace cupola::test

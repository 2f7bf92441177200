#include "support/netns_testbed.hpp"

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "support/test_support.hpp"

namespace cupola::test {

namespace fs = std::filesystem;

namespace {

std::atomic<int> g_counter{0};

std::string quote(const std::string& word) {
    std::string out = "'";
    for (char c : word) {
        if (c == '\'')
            out += "'\\''";
        else
            out += c;
    }
    return out + "'";
}

// Absolute path of a program found in PATH or the usual system folders; "" when none.
std::string find_program(const std::string& name) {
    std::vector<std::string> dirs;
    if (const char* path = std::getenv("PATH")) {
        std::stringstream ss(path);
        std::string d;
        while (std::getline(ss, d, ':'))
            if (!d.empty()) dirs.push_back(d);
    }
    for (const char* d : {"/usr/sbin", "/sbin", "/usr/bin", "/bin"}) dirs.emplace_back(d);
    for (const auto& d : dirs) {
        const std::string p = d + "/" + name;
        if (::access(p.c_str(), X_OK) == 0) return p;
    }
    return "";
}

const std::string& ip_program() {
    static const std::string p = [] {
        std::string f = find_program("ip");
        return f.empty() ? std::string("ip") : f;
    }();
    return p;
}

// Runs a command line in the root namespace with stderr merged into the output.
std::pair<int, std::string> sh(const std::string& command) { return run_shell(command + " 2>&1"); }

std::string ip_cmd(const std::string& args) { return quote(ip_program()) + " " + args; }

std::string netns_exec(const std::string& ns, const std::string& rest) {
    return ip_cmd("netns exec " + quote(ns) + " " + rest);
}

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) s.pop_back();
    return s;
}

std::vector<std::string> list_netns() {
    std::vector<std::string> out;
    auto [rc, text] = run_shell(ip_cmd("netns list 2>/dev/null"));
    if (rc != 0) return out;
    std::stringstream ss(text);
    std::string line;
    while (std::getline(ss, line)) {
        std::stringstream ls(line);
        std::string name;
        if (ls >> name) out.push_back(name);  // "name (id: N)" or "name"
    }
    return out;
}

bool valid_host_name(const std::string& n) {
    if (n.empty()) return false;
    for (char c : n)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
    return true;
}

}  // namespace

std::vector<std::string> remove_stale_netns() {
    static const std::regex kOurs("^cpl([0-9]+)-.*");
    std::vector<std::string> removed;
    for (const auto& name : list_netns()) {
        std::smatch m;
        if (!std::regex_match(name, m, kOurs)) continue;
        const std::string pid = m[1].str();
        if (pid == std::to_string(::getpid())) continue;
        std::error_code ec;
        if (fs::exists("/proc/" + pid, ec)) continue;
        // Another test process may be removing the same one at the same moment: ignore failures.
        run_shell(ip_cmd("netns del " + quote(name) + " >/dev/null 2>&1"));
        removed.push_back(name);
    }
    return removed;
}

std::string NetnsTestbed::unavailable_reason() {
    static const std::string reason = []() -> std::string {
        if (::geteuid() != 0)
            return "network-namespace test bed needs root (euid is " + std::to_string(::geteuid()) + ")";
        if (find_program("ip").empty()) return "network-namespace test bed needs `ip` (iproute2), not found";
        if (find_program("nft").empty()) return "network-namespace test bed needs `nft` (nftables), not found";
        const std::string ns = "cpl" + std::to_string(::getpid()) + "-probe" + std::to_string(g_counter++);
        std::string why;
        const std::vector<std::string> steps = {
            ip_cmd("netns add " + quote(ns)),
            ip_cmd("-n " + quote(ns) + " link add pa type veth peer name pb"),
            ip_cmd("-n " + quote(ns) + " link add br0 type bridge mcast_snooping 0"),
            netns_exec(ns, "nft add table inet cupola_probe"),
        };
        for (const auto& cmd : steps) {
            auto [rc, out] = sh(cmd);
            if (rc != 0) {
                why = "network-namespace test bed unavailable: `" + cmd + "` failed (status " + std::to_string(rc) +
                      "): " + trim(out);
                break;
            }
        }
        run_shell(ip_cmd("netns del " + quote(ns) + " >/dev/null 2>&1"));
        return why;
    }();
    return reason;
}

void NetnsTestbed::must(const std::string& command) const {
    auto [rc, out] = sh(command);
    if (rc != 0)
        throw std::runtime_error("netns test bed: `" + command + "` failed (status " + std::to_string(rc) +
                                 "): " + trim(out));
}

NetnsTestbed::NetnsTestbed(const std::string& tag, const std::vector<std::string>& host_names) {
    if (host_names.empty()) throw std::invalid_argument("netns test bed: no hosts");
    if (host_names.size() > 200) throw std::invalid_argument("netns test bed: more than 200 hosts");
    std::set<std::string> seen;
    for (const auto& n : host_names) {
        if (!valid_host_name(n))
            throw std::invalid_argument("netns test bed: bad host name '" + n + "' (want [A-Za-z0-9_-]+)");
        if (!seen.insert(n).second) throw std::invalid_argument("netns test bed: host '" + n + "' given twice");
    }
    std::string t;
    for (char c : tag)
        if ((std::isalnum(static_cast<unsigned char>(c)) || c == '_') && t.size() < 12) t += c;
    const std::string prefix = "cpl" + std::to_string(::getpid()) + "-" + t + std::to_string(g_counter++);
    switch_ns_ = prefix + "--sw";
    for (size_t i = 0; i < host_names.size(); ++i)
        hosts_.push_back({host_names[i], prefix + "-" + host_names[i], "10.77.0." + std::to_string(i + 2)});

    // Creates a namespace; one already there with our exact name (pid + fresh counter) can only be a
    // leftover of a dead process that had the same pid, so it is replaced.
    auto add_ns = [this](const std::string& ns) {
        created_.push_back(ns);
        auto [rc, out] = sh(ip_cmd("netns add " + quote(ns)));
        if (rc != 0) {
            run_shell(ip_cmd("netns del " + quote(ns) + " >/dev/null 2>&1"));
            must(ip_cmd("netns add " + quote(ns)));
        }
    };

    try {
        remove_stale_netns();
        add_ns(switch_ns_);
        const std::string sw = "-n " + quote(switch_ns_) + " ";
        must(ip_cmd(sw + "link add br0 type bridge mcast_snooping 0 stp_state 0 forward_delay 0"));
        must(ip_cmd(sw + "link set br0 up"));
        for (size_t i = 0; i < hosts_.size(); ++i) {
            const NetnsHost& h = hosts_[i];
            add_ns(h.ns);
            const std::string port = "p" + std::to_string(i);
            const std::string hn = "-n " + quote(h.ns) + " ";
            must(ip_cmd(sw + "link add " + port + " type veth peer name eth0 netns " + quote(h.ns)));
            must(ip_cmd(sw + "link set " + port + " master br0 up"));
            must(ip_cmd(hn + "link set lo up"));
            must(ip_cmd(hn + "addr add " + h.address + "/24 dev eth0"));
            must(ip_cmd(hn + "link set eth0 multicast on up"));
            must(ip_cmd(hn + "route replace 224.0.0.0/4 dev eth0"));
        }
    } catch (...) {
        destroy();
        throw;
    }
}

NetnsTestbed::~NetnsTestbed() { destroy(); }

void NetnsTestbed::destroy() noexcept {
    try {
        for (auto it = created_.rbegin(); it != created_.rend(); ++it)
            run_shell(ip_cmd("netns del " + quote(*it) + " >/dev/null 2>&1"));
    } catch (...) {}
    created_.clear();
}

const NetnsHost& NetnsTestbed::host(const std::string& name) const {
    for (const auto& h : hosts_)
        if (h.name == name) return h;
    throw std::runtime_error("netns test bed: no host named '" + name + "'");
}

std::vector<std::string> NetnsTestbed::namespaces() const {
    std::vector<std::string> out{switch_ns_};
    for (const auto& h : hosts_) out.push_back(h.ns);
    return out;
}

std::vector<std::string> NetnsTestbed::exec_prefix(const std::string& name) const {
    return {ip_program(), "netns", "exec", host(name).ns};
}

void NetnsTestbed::set_loss(const std::string& name, double percent, int port_lo, int port_hi) {
    const NetnsHost& h = host(name);
    if (!(percent >= 0.0 && percent <= 100.0))
        throw std::invalid_argument("netns test bed: loss percent " + std::to_string(percent) + " not in [0, 100]");
    if (port_lo < 1 || port_hi > 65535 || port_lo > port_hi)
        throw std::invalid_argument("netns test bed: bad port range " + std::to_string(port_lo) + "-" +
                                    std::to_string(port_hi));
    // "add table" is a no-op when it exists, so "add; delete" removes any earlier rule; one nft
    // transaction, applied atomically.
    std::string script = "add table inet cupola_loss\ndelete table inet cupola_loss\n";
    if (percent > 0.0) {
        const long threshold = std::lround(percent * 10.0);
        const std::string ports =
            port_lo == port_hi ? std::to_string(port_lo) : std::to_string(port_lo) + "-" + std::to_string(port_hi);
        script +=
            "add table inet cupola_loss\n"
            "add chain inet cupola_loss input { type filter hook input priority 0; policy accept; }\n"
            "add rule inet cupola_loss input udp dport " +
            ports +
            (threshold >= 1000 ? std::string()  // nft rejects "< 1000" (out of the numgen range)
                               : " numgen random mod 1000 < " + std::to_string(threshold)) +
            " counter drop\n";
    }
    must("printf '%s' " + quote(script) + " | " + netns_exec(h.ns, "nft -f -"));
}

uint64_t NetnsTestbed::dropped_packets(const std::string& name) const {
    const NetnsHost& h = host(name);
    auto [rc, out] = run_shell(netns_exec(h.ns, "nft list table inet cupola_loss 2>/dev/null"));
    if (rc != 0) return 0;  // no loss rule
    static const std::regex kCounter("counter packets ([0-9]+)");
    std::smatch m;
    if (!std::regex_search(out, m, kCounter))
        throw std::runtime_error("netns test bed: no counter in the loss rule of " + name + ": " + out);
    return std::stoull(m[1].str());
}

void NetnsTestbed::link_down(const std::string& name) {
    must(ip_cmd("-n " + quote(host(name).ns) + " link set eth0 down"));
}

void NetnsTestbed::link_up(const std::string& name) {
    const std::string hn = "-n " + quote(host(name).ns) + " ";
    must(ip_cmd(hn + "link set eth0 up"));
    // Taking the link down flushed the routes through it; the subnet route comes back with the
    // address, the multicast one has to be added again.
    must(ip_cmd(hn + "route replace 224.0.0.0/4 dev eth0"));
}

std::pair<int, std::string> NetnsTestbed::run(const std::string& name, const std::string& command) const {
    return run_shell(netns_exec(host(name).ns, "sh -c " + quote(command)));
}

int NetnsTestbed::open_socket(const std::string& name, int type, int domain) const {
    const std::string& ns = host(name).ns;
    int fd = -1;
    std::string error;
    // The network namespace is per thread: a short-lived thread enters the host's namespace and
    // creates the socket there; the socket keeps that namespace for its whole life.
    std::thread t([&] {
        int nsfd = -1;
        for (const char* dir : {"/run/netns/", "/var/run/netns/"}) {
            nsfd = ::open((std::string(dir) + ns).c_str(), O_RDONLY | O_CLOEXEC);
            if (nsfd >= 0) break;
        }
        if (nsfd < 0) {
            error = "cannot open namespace " + ns + ": " + std::strerror(errno);
            return;
        }
        if (::setns(nsfd, CLONE_NEWNET) != 0) {
            error = "setns(" + ns + ") failed: " + std::strerror(errno);
            ::close(nsfd);
            return;
        }
        ::close(nsfd);
        fd = ::socket(domain, type | SOCK_CLOEXEC, 0);
        if (fd < 0) error = std::string("socket() failed: ") + std::strerror(errno);
    });
    t.join();
    if (fd < 0) throw std::runtime_error("netns test bed: socket in " + name + ": " + error);
    return fd;
}

}  // namespace cupola::test

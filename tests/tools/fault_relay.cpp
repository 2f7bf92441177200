// cupola-fault-relay: a fault-injecting UDP relay for the cluster network tests.
//
// Why: the cluster tests run the master and the slaves in network namespaces and want to see
// how the protocol copes with an imperfect network. The usual tool for that is netem (tc qdisc
// ... netem delay/reorder/duplicate), but the test kernel is built without it. So the tests put
// this process on a host between the master and the slaves instead: it receives the real UDP
// datagrams (unicast, or multicast after joining the group), holds each one for a while and
// forwards it, unchanged, to another address (unicast or multicast on a chosen interface).
//
// Faults, each decided per datagram from a seeded PRNG (so a run can be repeated with --seed):
//   --delay-ms D --jitter-ms J   held D + uniform[0, J] ms (jitter alone already reorders
//                                datagrams that arrive closer together than J)
//   --reorder P                  with probability P held an extra uniform[3, 10] ms, so later
//                                datagrams overtake it
//   --duplicate P                with probability P sent twice, the copy 0..2 ms after the first
//   --drop P                     with probability P not forwarded at all
//
// It is protocol-agnostic: the payload is never parsed. It relays one direction only (run a
// second relay for the way back); the forwarded datagrams carry the relay's source address.
//
// Design: one thread; a priority queue of held datagrams ordered by release time; ppoll() on the
// listening socket with a timeout up to the next release (or the next stats write). Datagrams go
// out through a separate socket (unbound, or bound to --out-iface:0) with sendto().
//
// --stats FILE gets a JSON object, rewritten atomically (temp file + rename) right after start-up
// (so its appearance means "listening"), every 200 ms and at exit:
//   received    datagrams received
//   forwarded   datagrams sent (duplicate copies included)
//   duplicated  datagrams that were (or are to be) sent a second time
//   reordered   datagrams forwarded after a datagram that arrived later than them
//   dropped     datagrams dropped on purpose (--drop)
//   max_hold_ms longest time between receiving a datagram and sending it (or its copy)
//   held        copies waiting in the queue now; received - dropped + duplicated
//               == forwarded + held
//   send_errors sendto() failures (ignored: the datagram counts as lost, not as forwarded)
//   max_late_ms longest time a copy went out after its planned release (the relay's own noise:
//               scheduling on a busy machine)
//   seed, running (false in the final write, after SIGTERM/SIGINT or --duration-s)
// Datagrams still held at exit are discarded (like pulling the cable); "held" says how many.
#include <CLI/CLI.hpp>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <spdlog/cfg/env.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <queue>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using Millis = std::chrono::duration<double, std::milli>;

volatile sig_atomic_t g_stop_signal = 0;
void on_signal(int sig) { g_stop_signal = sig; }

[[noreturn]] void fail(const std::string& what) { throw std::system_error(errno, std::generic_category(), what); }

in_addr parse_ipv4(const std::string& s, const std::string& what) {
    in_addr a{};
    if (inet_pton(AF_INET, s.c_str(), &a) != 1)
        throw std::invalid_argument(what + ": \"" + s + "\" is not an IPv4 address");
    return a;
}

sockaddr_in parse_host_port(const std::string& s, const std::string& what) {
    const auto colon = s.rfind(':');
    if (colon == std::string::npos) throw std::invalid_argument(what + ": \"" + s + "\" is not of the form IPv4:PORT");
    const std::string port_text = s.substr(colon + 1);
    size_t used = 0;
    int port = -1;
    try {
        port = std::stoi(port_text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != port_text.size() || port < 1 || port > 65535)
        throw std::invalid_argument(what + ": \"" + s + "\" has no valid port (1..65535)");
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr = parse_ipv4(s.substr(0, colon), what);
    return a;
}

bool is_multicast(in_addr a) { return IN_MULTICAST(ntohl(a.s_addr)); }

std::string to_string(const sockaddr_in& a) {
    char buf[INET_ADDRSTRLEN] = {};
    inet_ntop(AF_INET, &a.sin_addr, buf, sizeof buf);
    return std::string(buf) + ":" + std::to_string(ntohs(a.sin_port));
}

class Fd {
public:
    Fd() : fd_(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)) {
        if (fd_ < 0) fail("socket(AF_INET, SOCK_DGRAM)");
    }
    ~Fd() { ::close(fd_); }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    int get() const { return fd_; }

    template <typename T>
    void option(int level, int name, const T& value, const char* what) {
        if (setsockopt(fd_, level, name, &value, sizeof value) != 0) fail(std::string("setsockopt(") + what + ")");
    }
    // A big buffer so that a burst (a whole frame's datagrams) is not lost in front of the relay.
    void buffer(int force_name, int name, int bytes) {
        if (setsockopt(fd_, SOL_SOCKET, force_name, &bytes, sizeof bytes) != 0)
            setsockopt(fd_, SOL_SOCKET, name, &bytes, sizeof bytes);  // best effort without CAP_NET_ADMIN
    }
    void bind(const sockaddr_in& a) {
        if (::bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) fail("bind(" + to_string(a) + ")");
    }

private:
    int fd_;
};

struct Held {
    Clock::time_point release;
    uint64_t seq;  // arrival order
    int copy;      // 0: the datagram, 1: its duplicate
    Clock::time_point arrival;
    std::shared_ptr<const std::vector<uint8_t>> data;
};
struct LaterFirst {
    bool operator()(const Held& a, const Held& b) const {
        if (a.release != b.release) return a.release > b.release;
        if (a.seq != b.seq) return a.seq > b.seq;
        return a.copy > b.copy;
    }
};

struct Stats {
    uint64_t received = 0, forwarded = 0, duplicated = 0, reordered = 0, dropped = 0, send_errors = 0;
    double max_hold_ms = 0.0;
    double max_late_ms = 0.0;  // how much later than planned a copy went out (the relay's own noise)
};

void write_stats(const std::string& path, const Stats& s, size_t held, uint64_t seed, bool running) {
    if (path.empty()) return;
    const nlohmann::json j = {{"received", s.received},
                              {"forwarded", s.forwarded},
                              {"duplicated", s.duplicated},
                              {"reordered", s.reordered},
                              {"dropped", s.dropped},
                              {"max_hold_ms", s.max_hold_ms},
                              {"held", held},
                              {"send_errors", s.send_errors},
                              {"max_late_ms", s.max_late_ms},
                              {"seed", seed},
                              {"running", running}};
    const std::string tmp = path + ".tmp." + std::to_string(::getpid());
    {
        std::ofstream f(tmp, std::ios::trunc);
        if (!f) throw std::runtime_error("cannot write stats file " + tmp);
        f << j.dump() << '\n';
        if (!f.flush()) throw std::runtime_error("cannot write stats file " + tmp);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + ec.message());
}

timespec to_timespec(Clock::duration d) {
    if (d < Clock::duration::zero()) d = Clock::duration::zero();
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(d).count();
    return timespec{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
}

struct Options {
    std::string listen, join, iface, to, out_iface, stats;
    double delay_ms = 0, jitter_ms = 0, reorder = 0, duplicate = 0, drop = 0, duration_s = 0;
    std::optional<uint64_t> seed;
    bool verbose = false;
};

int run(const Options& o) {
    // ---- addresses and sockets ----
    const sockaddr_in listen_addr = parse_host_port(o.listen, "--listen");
    const sockaddr_in to_addr = parse_host_port(o.to, "--to");
    if (!o.join.empty()) {
        const in_addr group = parse_ipv4(o.join, "--join");
        if (!is_multicast(group)) throw std::invalid_argument("--join: " + o.join + " is not a multicast group");
        parse_ipv4(o.iface, "--iface");
        if (is_multicast(listen_addr.sin_addr) && listen_addr.sin_addr.s_addr != group.s_addr)
            throw std::invalid_argument("--listen " + o.listen + " is a different group from --join " + o.join);
    } else if (is_multicast(listen_addr.sin_addr)) {
        throw std::invalid_argument("--listen " + o.listen + " is a multicast group: add --join GROUP --iface IFADDR");
    }

    Fd in;
    if (!o.join.empty()) {
        in.option(SOL_SOCKET, SO_REUSEADDR, 1, "SO_REUSEADDR");          // the group's port may be shared
        in.option(IPPROTO_IP, IP_MULTICAST_ALL, 0, "IP_MULTICAST_ALL");  // only the group we joined
    }
    in.buffer(SO_RCVBUFFORCE, SO_RCVBUF, 16 << 20);
    in.bind(listen_addr);
    if (!o.join.empty()) {
        ip_mreq m{};
        m.imr_multiaddr = parse_ipv4(o.join, "--join");
        m.imr_interface = parse_ipv4(o.iface, "--iface");
        if (setsockopt(in.get(), IPPROTO_IP, IP_ADD_MEMBERSHIP, &m, sizeof m) != 0)
            fail("IP_ADD_MEMBERSHIP " + o.join + " on " + o.iface);
    }

    Fd out;
    out.buffer(SO_SNDBUFFORCE, SO_SNDBUF, 16 << 20);
    if (!o.out_iface.empty()) {
        sockaddr_in local{};
        local.sin_family = AF_INET;
        local.sin_addr = parse_ipv4(o.out_iface, "--out-iface");
        out.bind(local);
    }
    if (is_multicast(to_addr.sin_addr)) {
        if (!o.out_iface.empty())
            out.option(IPPROTO_IP, IP_MULTICAST_IF, parse_ipv4(o.out_iface, "--out-iface"), "IP_MULTICAST_IF");
        else
            spdlog::warn("--to {} is multicast but no --out-iface given: the routing table picks the interface", o.to);
        out.option(IPPROTO_IP, IP_MULTICAST_LOOP, static_cast<unsigned char>(0), "IP_MULTICAST_LOOP");
        out.option(IPPROTO_IP, IP_MULTICAST_TTL, static_cast<unsigned char>(1), "IP_MULTICAST_TTL");
    }

    // Wake-ups as close to the release times as the kernel allows (the default slack is 50 us).
    prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);

    // ---- signals: blocked except while waiting in ppoll, so none is missed ----
    sigset_t block{}, wait_mask{};
    sigemptyset(&block);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGINT);
    if (sigprocmask(SIG_BLOCK, &block, &wait_mask) != 0) fail("sigprocmask");
    sigdelset(&wait_mask, SIGTERM);
    sigdelset(&wait_mask, SIGINT);
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGTERM, &sa, nullptr);
    sigaction(SIGINT, &sa, nullptr);

    // ---- fault model ----
    const uint64_t seed = o.seed ? *o.seed : (uint64_t{std::random_device{}()} << 32 | std::random_device{}());
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto ms = [](double v) { return std::chrono::duration_cast<Clock::duration>(Millis(v)); };

    spdlog::info("relaying {}{} -> {}{}; delay {} ms + jitter [0, {}] ms, reorder {}, duplicate {}, drop {}, seed {}",
                 o.listen, o.join.empty() ? "" : " (joined " + o.join + " on " + o.iface + ")", o.to,
                 o.out_iface.empty() ? "" : " via " + o.out_iface, o.delay_ms, o.jitter_ms, o.reorder, o.duplicate,
                 o.drop, seed);

    std::priority_queue<Held, std::vector<Held>, LaterFirst> queue;
    Stats stats;
    uint64_t next_seq = 0;
    int64_t max_forwarded_seq = -1;
    std::vector<uint8_t> buf(65536);

    const auto start = Clock::now();
    const std::optional<Clock::time_point> end =
        o.duration_s > 0 ? std::optional(start + ms(o.duration_s * 1000.0)) : std::nullopt;
    const auto stats_period = std::chrono::milliseconds(200);
    auto next_stats = start + stats_period;
    write_stats(o.stats, stats, 0, seed, true);

    auto receive_all = [&] {
        for (int n = 0; n < 1024; ++n) {  // bounded, so that due datagrams still go out under load
            sockaddr_in from{};
            socklen_t len = sizeof from;
            const ssize_t r = ::recvfrom(in.get(), buf.data(), buf.size(), MSG_DONTWAIT | MSG_TRUNC,
                                         reinterpret_cast<sockaddr*>(&from), &len);
            const auto now = Clock::now();
            if (r < 0) {
                if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR || errno == ECONNREFUSED) return;
                fail("recvfrom");
            }
            if (static_cast<size_t>(r) > buf.size()) {  // cannot happen for IPv4 UDP
                spdlog::warn("truncated a {}-byte datagram from {}", r, to_string(from));
                continue;
            }
            ++stats.received;
            // Always draw the same numbers per datagram, so a seed gives the same faults whatever
            // the probabilities.
            const bool drop = unit(rng) < o.drop;
            const double jitter = unit(rng) * o.jitter_ms;
            const bool reorder = unit(rng) < o.reorder;
            const double extra = 3.0 + 7.0 * unit(rng);
            const bool dup = unit(rng) < o.duplicate;
            const double dup_after = 2.0 * unit(rng);
            const uint64_t seq = next_seq++;
            if (drop) {
                ++stats.dropped;
                spdlog::trace("#{}: dropped", seq);
                continue;
            }
            auto data = std::make_shared<const std::vector<uint8_t>>(buf.begin(), buf.begin() + r);
            const auto release = now + ms(o.delay_ms + jitter + (reorder ? extra : 0.0));
            queue.push(Held{release, seq, 0, now, data});
            if (dup) {
                ++stats.duplicated;
                queue.push(Held{release + ms(dup_after), seq, 1, now, data});
            }
            spdlog::trace("#{}: {} bytes from {}, held {:.2f} ms{}{}", seq, r, to_string(from),
                          Millis(release - now).count(), reorder ? " (reordered)" : "", dup ? " (duplicated)" : "");
        }
    };

    auto send_due = [&] {
        while (!queue.empty()) {
            const auto now = Clock::now();
            if (queue.top().release > now) return;
            const Held h = queue.top();
            queue.pop();
            const ssize_t r = ::sendto(out.get(), h.data->data(), h.data->size(), 0,
                                       reinterpret_cast<const sockaddr*>(&to_addr), sizeof to_addr);
            if (r < 0) {
                if (errno == EINTR) {  // signals are blocked here, but be safe: retry
                    queue.push(h);
                    continue;
                }
                if (stats.send_errors++ < 10 || stats.send_errors % 1000 == 0)
                    spdlog::warn("sendto({}) failed: {} ({} send errors so far)", o.to, std::strerror(errno),
                                 stats.send_errors);
                continue;
            }
            ++stats.forwarded;
            const auto seq = static_cast<int64_t>(h.seq);
            if (h.copy == 0 && seq < max_forwarded_seq) ++stats.reordered;
            max_forwarded_seq = std::max(max_forwarded_seq, seq);
            const auto sent = Clock::now();
            stats.max_hold_ms = std::max(stats.max_hold_ms, Millis(sent - h.arrival).count());
            stats.max_late_ms = std::max(stats.max_late_ms, Millis(sent - h.release).count());
        }
    };

    while (g_stop_signal == 0) {
        const auto now = Clock::now();
        if (end && now >= *end) break;
        if (now >= next_stats) {
            write_stats(o.stats, stats, queue.size(), seed, true);
            next_stats = now + stats_period;
        }
        auto wake = next_stats;
        if (!queue.empty()) wake = std::min(wake, queue.top().release);
        if (end) wake = std::min(wake, *end);
        pollfd p{in.get(), POLLIN, 0};
        const timespec timeout = to_timespec(wake - now);
        const int r = ::ppoll(&p, 1, &timeout, &wait_mask);
        if (r < 0 && errno != EINTR) fail("ppoll");
        if (r > 0) {
            if (p.revents & (POLLERR | POLLNVAL)) {
                int err = 0;
                socklen_t len = sizeof err;
                getsockopt(in.get(), SOL_SOCKET, SO_ERROR, &err, &len);  // clears a pending ICMP error
            }
            if (p.revents & POLLIN) receive_all();
        }
        send_due();
    }

    if (g_stop_signal != 0) spdlog::info("stopping on signal {}", static_cast<int>(g_stop_signal));
    write_stats(o.stats, stats, queue.size(), seed, false);
    spdlog::info(
        "received {}, forwarded {}, duplicated {}, reordered {}, dropped {}, send errors {}, max hold "
        "{:.2f} ms; {} held copies discarded",
        stats.received, stats.forwarded, stats.duplicated, stats.reordered, stats.dropped, stats.send_errors,
        stats.max_hold_ms, queue.size());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "cupola-fault-relay: forward UDP datagrams from --listen to --to, injecting delay, jitter, "
        "reordering, duplication and drops (a stand-in for netem, which the test kernel lacks)"};
    Options o;
    uint64_t seed = 0;
    app.add_option("--listen", o.listen, "address to receive on, IPv4:PORT (a multicast group with --join)")
        ->required();
    auto* join = app.add_option("--join", o.join, "multicast group to join (the --listen address, or 0.0.0.0 there)");
    auto* iface = app.add_option("--iface", o.iface, "local interface address to join the group on");
    join->needs(iface);
    iface->needs(join);
    app.add_option("--to", o.to, "where to forward, IPv4:PORT (unicast or multicast)")->required();
    app.add_option("--out-iface", o.out_iface,
                   "local address to send from (bound as IFADDR:0; IP_MULTICAST_IF for a multicast --to)");
    app.add_option("--delay-ms", o.delay_ms, "fixed delay for every datagram (ms)")->check(CLI::Range(0.0, 60000.0));
    app.add_option("--jitter-ms", o.jitter_ms, "plus a uniform[0, J] ms random delay")->check(CLI::Range(0.0, 60000.0));
    app.add_option("--reorder", o.reorder, "probability of holding a datagram an extra 3..10 ms")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--duplicate", o.duplicate, "probability of sending a datagram twice (copy 0..2 ms later)")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--drop", o.drop, "probability of dropping a datagram")->check(CLI::Range(0.0, 1.0));
    auto* seed_opt = app.add_option("--seed", seed, "PRNG seed (default: random; logged and in the stats)");
    app.add_option("--stats", o.stats, "JSON stats file, rewritten atomically every 200 ms and at exit");
    app.add_option("--duration-s", o.duration_s, "exit after this many seconds (0 or absent: run until SIGTERM/SIGINT)")
        ->check(CLI::NonNegativeNumber);
    app.add_flag("-v,--verbose", o.verbose, "debug logging (SPDLOG_LEVEL=trace logs every datagram)");
    CLI11_PARSE(app, argc, argv);
    if (seed_opt->count() > 0) o.seed = seed;

    auto logger = spdlog::stderr_color_mt("fault-relay");
    logger->set_pattern("[%H:%M:%S.%e] [fault-relay] [%^%l%$] %v");
    spdlog::set_default_logger(logger);
    spdlog::set_level(o.verbose ? spdlog::level::debug : spdlog::level::info);
    spdlog::cfg::load_env_levels();

    try {
        return run(o);
    } catch (const std::invalid_argument& e) {
        spdlog::error("{}", e.what());
        return 2;
    } catch (const std::exception& e) {
        spdlog::error("{}", e.what());
        return 1;
    }
}

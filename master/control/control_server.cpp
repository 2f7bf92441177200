#include "control_server.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "util/monotonic_clock.hpp"

namespace cupola {

namespace {
constexpr size_t kMaxLine = 1024;
constexpr size_t kMaxClients = 32;

sockaddr_un socket_address(const std::string& path) {
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    if (path.size() >= sizeof a.sun_path)
        throw std::runtime_error("control socket \"" + path + "\": path longer than " +
                                 std::to_string(sizeof a.sun_path - 1) + " bytes");
    std::memcpy(a.sun_path, path.c_str(), path.size() + 1);
    return a;
}
}  // namespace

ControlServer::ControlServer(const std::string& path) : path_(path) {
    if (pipe2(wake_pipe_, O_CLOEXEC | O_NONBLOCK) != 0)
        throw std::runtime_error("control: pipe: " + std::string(std::strerror(errno)));
    try {
        open_listener(path);
    } catch (...) {
        close(wake_pipe_[0]);
        close(wake_pipe_[1]);
        throw;
    }
    thread_ = std::thread([this] { loop(); });
}

void ControlServer::open_listener(const std::string& path) {
    if (path == "-") {
        clients_.push_back({next_id_++, STDIN_FILENO, STDOUT_FILENO, true, {}});
    } else {
        const sockaddr_un addr = socket_address(path);
        struct stat st {};
        if (lstat(path.c_str(), &st) == 0) {
            if (!S_ISSOCK(st.st_mode))
                throw std::runtime_error("control socket \"" + path + "\": a file that is not a socket is in the way");
            // A socket file: live (another master listens) or stale (left by one that died).
            int probe = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
            const bool live = probe >= 0 && connect(probe, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
            if (probe >= 0) close(probe);
            if (live) throw std::runtime_error("control socket \"" + path + "\": another process is listening on it");
            unlink(path.c_str());
        }
        listen_fd_ = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
        if (listen_fd_ < 0) throw std::runtime_error("control socket: " + std::string(std::strerror(errno)));
        if (bind(listen_fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 ||
            listen(listen_fd_, 8) != 0) {
            const std::string why = std::strerror(errno);
            close(listen_fd_);
            throw std::runtime_error("control socket \"" + path + "\": cannot listen: " + why);
        }
        chmod(path.c_str(), 0660);
    }
}

ControlServer::~ControlServer() {
    stop_ = true;
    [[maybe_unused]] auto n = write(wake_pipe_[1], "x", 1);
    if (thread_.joinable()) thread_.join();
    for (auto& c : clients_)
        if (!c.stdio) close(c.fd);
    if (listen_fd_ >= 0) {
        close(listen_fd_);
        unlink(path_.c_str());
    }
    close(wake_pipe_[0]);
    close(wake_pipe_[1]);
}

std::vector<ControlRequest> ControlServer::take() {
    std::lock_guard lock(mutex_);
    std::vector<ControlRequest> out;
    out.swap(pending_);
    return out;
}

void ControlServer::reply(uint64_t client, const std::string& line) {
    std::lock_guard lock(mutex_);
    for (size_t i = 0; i < clients_.size(); ++i) {
        Client& c = clients_[i];
        if (c.id != client) continue;
        if (c.outstanding > 0) --c.outstanding;
        const std::string text = line + "\n";
        // Never block the frame loop: a reply goes out whole at once or is lost. A socket client
        // that cannot take it is disconnected (a half-written line would garble the next one).
        pollfd p{c.out_fd, POLLOUT, 0};
        ssize_t n = -1;
        if (poll(&p, 1, 0) == 1 && (p.revents & POLLOUT))
            n = c.stdio ? write(c.out_fd, text.data(), text.size())
                        : send(c.out_fd, text.data(), text.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n != static_cast<ssize_t>(text.size())) {
            spdlog::warn("control: reply to client {} lost ({})", client,
                         n < 0 ? (errno ? std::strerror(errno) : "not writable") : "partly written");
            if (!c.stdio) shutdown(c.fd, SHUT_RDWR);  // the reader sees the end and forgets it
        }
        if (c.eof && c.outstanding == 0) close_client(i);  // its input ended: all answered now
        return;
    }
}

void ControlServer::close_client(size_t index) {
    Client& c = clients_[index];
    if (!c.stdio) close(c.fd);
    spdlog::debug("control: client {} left", c.id);
    clients_.erase(clients_.begin() + static_cast<long>(index));
}

void ControlServer::loop() {
    while (!stop_) {
        std::vector<pollfd> fds;
        std::vector<uint64_t> ids;
        build_poll_set(fds, ids);
        if (poll(fds.data(), fds.size(), 500) < 0) {
            if (errno == EINTR) continue;
            spdlog::error("control: poll: {}", std::strerror(errno));
            return;
        }
        if (fds[0].revents) return;  // woken to stop
        size_t first_client = 1;
        if (listen_fd_ >= 0) {
            first_client = 2;
            if (fds[1].revents & POLLIN) accept_client();
        }
        for (size_t i = first_client; i < fds.size(); ++i)
            if (fds[i].revents & (POLLIN | POLLHUP | POLLERR | POLLNVAL)) read_client(fds[i], ids[i - first_client]);
    }
}

void ControlServer::build_poll_set(std::vector<pollfd>& fds, std::vector<uint64_t>& ids) {
    std::lock_guard lock(mutex_);
    fds.push_back({wake_pipe_[0], POLLIN, 0});
    if (listen_fd_ >= 0) fds.push_back({listen_fd_, POLLIN, 0});
    for (const auto& c : clients_) {
        if (c.eof || c.outstanding >= kMaxOutstanding) continue;
        fds.push_back({c.fd, POLLIN, 0});
        ids.push_back(c.id);
    }
}

void ControlServer::accept_client() {
    const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0 && errno != EAGAIN && errno != EINTR) {
        spdlog::warn("control: accept: {}", std::strerror(errno));  // e.g. out of descriptors
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    if (fd < 0) return;
    std::lock_guard lock(mutex_);
    if (clients_.size() >= kMaxClients) {
        const char* msg = "error too many control clients\n";
        [[maybe_unused]] auto n = send(fd, msg, std::strlen(msg), MSG_NOSIGNAL | MSG_DONTWAIT);
        close(fd);
    } else {
        clients_.push_back({next_id_++, fd, fd, false, {}});
        spdlog::debug("control: client {} connected", clients_.back().id);
    }
}

void ControlServer::read_client(const pollfd& p, uint64_t id) {
    char buf[2048];
    const ssize_t n = (p.revents & POLLNVAL) ? 0 : read(p.fd, buf, sizeof buf);
    std::lock_guard lock(mutex_);
    size_t idx = 0;
    while (idx < clients_.size() && clients_[idx].id != id) ++idx;
    if (idx == clients_.size()) return;
    if (n <= 0) {
        if (n < 0 && (errno == EINTR || errno == EAGAIN)) return;
        if (clients_[idx].outstanding == 0)
            close_client(idx);
        else
            clients_[idx].eof = true;  // answered first, then forgotten (reply())
        return;
    }
    split_lines(clients_[idx], buf, static_cast<size_t>(n));
}

void ControlServer::split_lines(Client& c, const char* data, size_t n) {
    for (size_t k = 0; k < n; ++k) {
        const char ch = data[k];
        if (ch == '\n') {
            if (c.discarding) {
                c.discarding = false;
                ++refused_;
                pending_.push_back({c.id, std::string(kMaxLine + 1, 'x'), monotonic_ns()});  // answered as too long
                ++c.outstanding;
            } else {
                if (!c.buffer.empty() && c.buffer.back() == '\r') c.buffer.pop_back();
                pending_.push_back({c.id, std::move(c.buffer), monotonic_ns()});
                ++c.outstanding;
            }
            c.buffer.clear();
        } else if (!c.discarding) {
            c.buffer.push_back(ch);
            if (c.buffer.size() > kMaxLine) {
                c.discarding = true;
                c.buffer.clear();
            }
        }
    }
}

}  // namespace cupola

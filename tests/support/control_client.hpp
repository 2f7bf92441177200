#pragma once
// A client of the master's control socket for tests: connects, sends lines, reads reply lines
// (with a receive timeout, so a silent master fails the test instead of hanging it).
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <string>

namespace cupola::test {

class ControlClient {
public:
    explicit ControlClient(const std::string& path, int timeout_s = 5) {
        fd_ = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
        connected_ = fd_ >= 0 && connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
        timeval tv{timeout_s, 0};
        setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    }
    ~ControlClient() {
        if (fd_ >= 0) close(fd_);
    }
    ControlClient(const ControlClient&) = delete;
    ControlClient& operator=(const ControlClient&) = delete;

    bool connected() const { return connected_; }
    int fd() const { return fd_; }
    bool send_raw(const std::string& s) {
        return send(fd_, s.data(), s.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(s.size());
    }
    // The next reply line, or "(no reply)" after the timeout or when the master closed.
    std::string read_line() {
        while (true) {
            const auto nl = pending_.find('\n');
            if (nl != std::string::npos) {
                std::string l = pending_.substr(0, nl);
                pending_.erase(0, nl + 1);
                return l;
            }
            char buf[4096];
            const ssize_t n = recv(fd_, buf, sizeof buf, 0);
            if (n <= 0) return "(no reply)";
            pending_.append(buf, static_cast<size_t>(n));
        }
    }
    // One command, its reply.
    std::string command(const std::string& line) { return send_raw(line + "\n") ? read_line() : "(send failed)"; }

private:
    int fd_ = -1;
    bool connected_ = false;
    std::string pending_;
};

}  // namespace cupola::test

#pragma once
// A real X server for window tests: Xvfb (Debian xvfb) on a display number it picks itself
// (-displayfd: it writes the number once it accepts connections), killed when the fixture ends.
// When Xvfb is not installed, or does not start, skip_reason() says why and the tests skip.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace cupola::test {

class XvfbDisplay {
public:
    XvfbDisplay(int width, int height) {
        const std::string xvfb = find_program("Xvfb");
        if (xvfb.empty()) {
            skip_ = "Xvfb is not installed (Debian package xvfb, scripts/setup.sh)";
            return;
        }
        int fds[2];
        if (::pipe(fds) != 0) {
            skip_ = "pipe() failed";
            return;
        }
        const std::string screen = std::to_string(width) + "x" + std::to_string(height) + "x24";
        pid_ = ::fork();
        if (pid_ == 0) {
            ::close(fds[0]);
            const int null = ::open("/dev/null", O_RDWR);
            ::dup2(null, 0);
            ::dup2(null, 1);
            ::dup2(null, 2);
            const std::string fd = std::to_string(fds[1]);
            ::execl(xvfb.c_str(), "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", screen.c_str(), "-nolisten", "tcp",
                    static_cast<char*>(nullptr));
            ::_exit(127);
        }
        ::close(fds[1]);
        name_ = read_display(fds[0]);
        ::close(fds[0]);
        if (name_.empty())
            skip_ = "Xvfb did not report a display within 10 s";
        else if (!accepts(name_.substr(1)))
            skip_ = "Xvfb on " + name_ + " accepts no connection within 5 s";
    }
    ~XvfbDisplay() {
        if (pid_ > 0) {
            ::kill(pid_, SIGTERM);
            int status = 0;
            ::waitpid(pid_, &status, 0);
        }
    }
    XvfbDisplay(const XvfbDisplay&) = delete;
    XvfbDisplay& operator=(const XvfbDisplay&) = delete;

    const std::string& name() const { return name_; }  // e.g. ":3"
    const std::string& skip_reason() const { return skip_; }

private:
    static std::string find_program(const std::string& name) {
        const char* path = std::getenv("PATH");
        std::string dirs = path ? path : "/usr/bin:/bin";
        for (size_t start = 0; start <= dirs.size();) {
            const size_t end = dirs.find(':', start);
            const std::string d = dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
            const std::string p = (d.empty() ? "." : d) + "/" + name;
            if (::access(p.c_str(), X_OK) == 0) return p;
            if (end == std::string::npos) break;
            start = end + 1;
        }
        return {};
    }
    // The server's local socket takes a connection (the X11 convention: /tmp/.X11-unix/X<N>).
    static bool accepts(const std::string& number) {
        const std::string path = "/tmp/.X11-unix/X" + number;
        for (int tries = 0; tries < 100; ++tries) {
            const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
            sockaddr_un a{};
            a.sun_family = AF_UNIX;
            std::snprintf(a.sun_path, sizeof a.sun_path, "%s", path.c_str());
            const bool ok = ::connect(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
            ::close(s);
            if (ok) return true;
            ::usleep(50000);
        }
        return false;
    }
    static std::string read_display(int fd) {
        std::string digits;
        for (int waited_ms = 0; waited_ms < 10000;) {
            pollfd p{fd, POLLIN, 0};
            if (::poll(&p, 1, 100) <= 0) {
                waited_ms += 100;
                continue;
            }
            char c = 0;
            if (::read(fd, &c, 1) != 1) break;  // Xvfb exited
            if (c == '\n') return digits.empty() ? std::string() : ":" + digits;
            digits += c;
        }
        return {};
    }

    pid_t pid_ = -1;
    std::string name_;
    std::string skip_;
};

}  // namespace cupola::test

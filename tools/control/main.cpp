// cupola-control: sends control commands to a running master's control socket and prints the
// replies. One command from the arguments, or one per line from standard input:
//   cupola-control /run/cupola/control.sock goto Moon
//   cupola-control /run/cupola/control.sock time rate 3600
//   printf 'pause\nstatus\n' | cupola-control /run/cupola/control.sock
// Exit status: 0 when every reply was "ok ...", 1 when one was "error ...", 2 when the master
// could not be reached or did not answer within --timeout seconds.
#include <CLI/CLI.hpp>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace {

// Reads one reply line; false on timeout or a closed connection.
bool read_line(int fd, std::string& pending, std::string& line, int timeout_ms) {
    while (true) {
        const auto nl = pending.find('\n');
        if (nl != std::string::npos) {
            line = pending.substr(0, nl);
            pending.erase(0, nl + 1);
            return true;
        }
        pollfd p{fd, POLLIN, 0};
        if (poll(&p, 1, timeout_ms) <= 0) return false;
        char buf[4096];
        const ssize_t n = read(fd, buf, sizeof buf);
        if (n <= 0) return false;
        pending.append(buf, static_cast<size_t>(n));
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Send control commands to a Cupola master (the command help lists them; see README.md)"};
    std::string socket_path;
    std::vector<std::string> words;
    double timeout_s = 10.0;
    app.add_option("socket", socket_path, "the master's control socket (cupola-master --control PATH)")->required();
    app.add_option("command", words, "a command, e.g. goto Moon (none: read commands from standard input)");
    app.add_option("--timeout", timeout_s, "seconds to wait for each reply")->check(CLI::Range(0.1, 3600.0));
    CLI11_PARSE(app, argc, argv);

    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    if (socket_path.size() >= sizeof addr.sun_path) {
        std::cerr << "cupola-control: socket path too long: " << socket_path << "\n";
        return 2;
    }
    std::memcpy(addr.sun_path, socket_path.c_str(), socket_path.size() + 1);
    const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0 || connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
        std::cerr << "cupola-control: cannot connect to " << socket_path << ": " << std::strerror(errno)
                  << " (is cupola-master running with --control " << socket_path << "?)\n";
        return 2;
    }
    std::vector<std::string> lines;
    if (!words.empty()) {
        std::string l;
        for (const auto& w : words) l += (l.empty() ? "" : " ") + w;
        lines.push_back(l);
    } else {
        for (std::string l; std::getline(std::cin, l);)
            if (!l.empty()) lines.push_back(l);
    }
    int rc = 0;
    std::string pending;
    for (const auto& l : lines) {
        const std::string out = l + "\n";
        if (send(fd, out.data(), out.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(out.size())) {
            std::cerr << "cupola-control: the master closed the connection\n";
            return 2;
        }
        std::string reply;
        if (!read_line(fd, pending, reply, static_cast<int>(timeout_s * 1000))) {
            std::cerr << "cupola-control: no reply to \"" << l << "\" within " << timeout_s << " s\n";
            return 2;
        }
        std::cout << reply << "\n";
        if (reply.rfind("ok", 0) != 0) rc = 1;
    }
    close(fd);
    return rc;
}

#pragma once
// Where control commands come from: a local (Unix domain, stream) socket that any number of
// clients (a console, a show-control system, a test) connect to, or the master's standard input.
// A thread reads lines; the frame loop takes them once per frame (take()) and answers each with
// one line (reply()). Lines longer than 1024 bytes are refused; a client that goes away is
// forgotten, its pending replies dropped; one whose input ended (stdin at EOF, a half-closed
// socket) is kept until its lines are answered. Replies never block the frame loop: a client that
// does not read loses them (and, on a socket, the connection).
#include <poll.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace cupola {

struct ControlRequest {
    uint64_t client = 0;       // whom to reply to
    std::string line;          // without the newline
    uint64_t received_ns = 0;  // monotonic_ns() when the line was complete
};

class ControlServer {
public:
    // path: a socket path (created with mode 0660; a stale socket file left by a dead master is
    // replaced, a live one is an error), or "-" for standard input / standard output.
    // Throws std::runtime_error naming the path and the reason when it cannot listen.
    explicit ControlServer(const std::string& path);
    ~ControlServer();
    ControlServer(const ControlServer&) = delete;
    ControlServer& operator=(const ControlServer&) = delete;

    std::vector<ControlRequest> take();
    void reply(uint64_t client, const std::string& line);
    const std::string& path() const { return path_; }
    uint64_t lines_refused() const { return refused_; }

private:
    struct Client {
        uint64_t id;
        int fd;      // read side
        int out_fd;  // write side (stdout for stdin)
        bool stdio;  // standard input / output: never closed here
        std::string buffer;
        bool discarding = false;  // inside an over-long line
        bool eof = false;         // no more input: kept until its pending lines are answered
        size_t outstanding = 0;   // lines taken or pending, not answered yet
    };
    // Clients with more unanswered lines than this are not read until the frame loop catches up.
    static constexpr size_t kMaxOutstanding = 64;
    void open_listener(const std::string& path);
    void loop();
    // Steps of loop(): the descriptors to wait on (ids: the clients', in the same order), a new
    // connection, one client's input (split into pending lines, under the lock).
    void build_poll_set(std::vector<pollfd>& fds, std::vector<uint64_t>& ids);
    void accept_client();
    void read_client(const pollfd& p, uint64_t id);
    void split_lines(Client& c, const char* data, size_t n);
    void close_client(size_t index);

    std::string path_;
    int listen_fd_ = -1;
    int wake_pipe_[2] = {-1, -1};
    std::mutex mutex_;
    std::vector<Client> clients_;
    std::vector<ControlRequest> pending_;
    uint64_t next_id_ = 1;
    std::atomic<uint64_t> refused_{0};
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

}  // namespace cupola

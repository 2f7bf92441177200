#pragma once
// Starting and supervising child processes (the loopback launcher and the tests run real
// master and slave processes). The child's stdout/stderr can go to a log file.
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace cupola {

class ChildProcess {
public:
    // argv[0] is the program path. env_unset: variables removed from the child's environment.
    ChildProcess(const std::vector<std::string>& argv, const std::string& log_file = "",
                 const std::vector<std::string>& env_unset = {});
    ~ChildProcess();  // kills (SIGKILL) and reaps a child still running
    ChildProcess(ChildProcess&& o) noexcept;
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;
    ChildProcess& operator=(ChildProcess&& o) noexcept;

    pid_t pid() const { return pid_; }
    bool running();
    // Exit code (128+signal when killed by a signal), or nothing when still running at the deadline.
    std::optional<int> wait_for(std::chrono::milliseconds timeout);
    void kill(int signal);

private:
    pid_t pid_ = -1;
    std::optional<int> status_;
};

// Directory of the running executable (to find sibling programs).
std::string executable_dir();

}  // namespace cupola

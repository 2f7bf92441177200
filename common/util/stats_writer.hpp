#pragma once
// The anomaly counters of a node, for the operator: written as one JSON object to a file
// (--stats; replaced atomically, so a monitor never reads half a file) about once a second, and
// logged as one line every `log_interval`.
#include <chrono>
#include <nlohmann/json.hpp>
#include <string>

namespace cupola {

class StatsWriter {
public:
    // path: "" writes no file. log_name: prefix of the log line.
    StatsWriter(std::string path, std::string log_name,
                std::chrono::milliseconds log_interval = std::chrono::seconds(10));

    // Call often; writes the file and/or logs when their interval has passed. `make` builds the
    // JSON only then.
    template <class Make>
    void tick(const Make& make) {
        const auto now = std::chrono::steady_clock::now();
        const bool file_due = !path_.empty() && now - last_file_ >= std::chrono::seconds(1);
        const bool log_due = now - last_log_ >= log_interval_;
        if (!file_due && !log_due) return;
        const nlohmann::json j = make();
        if (file_due) write_file(j), last_file_ = now;
        if (log_due) log_line(j), last_log_ = now;
    }
    // Writes the file now (at exit), whatever the interval.
    void write_now(const nlohmann::json& j);

private:
    void write_file(const nlohmann::json& j);
    void log_line(const nlohmann::json& j);

    std::string path_;
    std::string log_name_;
    std::chrono::milliseconds log_interval_;
    std::chrono::steady_clock::time_point last_file_{};
    std::chrono::steady_clock::time_point last_log_;
};

}  // namespace cupola

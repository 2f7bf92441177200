#include "util/stats_writer.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <fstream>

namespace cupola {

StatsWriter::StatsWriter(std::string path, std::string log_name, std::chrono::milliseconds log_interval)
    : path_(std::move(path)),
      log_name_(std::move(log_name)),
      log_interval_(log_interval),
      last_log_(std::chrono::steady_clock::now()) {}

void StatsWriter::write_now(const nlohmann::json& j) {
    if (!path_.empty()) write_file(j);
}

void StatsWriter::write_file(const nlohmann::json& j) {
    const std::string tmp = path_ + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        if (!out) {
            spdlog::warn("{}: cannot write the stats file {}", log_name_, tmp);
            return;
        }
        out << j.dump(2) << '\n';
    }
    if (std::rename(tmp.c_str(), path_.c_str()) != 0)
        spdlog::warn("{}: cannot replace the stats file {}", log_name_, path_);
}

void StatsWriter::log_line(const nlohmann::json& j) { spdlog::info("{}: stats {}", log_name_, j.dump()); }

}  // namespace cupola

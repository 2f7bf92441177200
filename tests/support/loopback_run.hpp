#pragma once
// Running real clusters from tests: a loopback run of a cluster config written here, the
// master's events file, and waiting on files that processes write.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "support/test_support.hpp"
#include "util/child_process.hpp"

namespace cupola::test {

// Writes `cluster` (plus the repo's key and generous timeouts) to dir/cluster.json, runs
// cupola-loopback for `frames` frames into dir/out and expects it to succeed; returns dir/out.
inline std::string run_loopback(const std::string& dir, nlohmann::json cluster, int frames) {
    cluster["key_file"] = source_path("configs/keys/loopback.key");
    cluster["network"]["channel_timeout_ms"] = 60000;
    cluster["network"]["hello_wait_ms"] = 60000;
    const std::string config = dir + "/cluster.json";
    write_text(config, cluster.dump(2));
    const std::string out = dir + "/out";
    ChildProcess p({bin_path("cupola-loopback"), "--config", config, "--frames", std::to_string(frames), "--out", out,
                    "--timeout", "500"},
                   dir + "/loopback.log", {"DISPLAY", "WAYLAND_DISPLAY", "SPDLOG_LEVEL"});
    EXPECT_EQ(p.wait_for(std::chrono::seconds(520)).value_or(-1), 0) << read_text(dir + "/loopback.log");
    return out;
}

// The master's events file (--events): one JSON object per line.
inline std::vector<nlohmann::json> read_events(const std::string& path) {
    std::vector<nlohmann::json> out;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line))
        if (!line.empty()) out.push_back(nlohmann::json::parse(line, nullptr, false));
    return out;
}

inline bool wait_until(const std::function<bool()>& cond, std::chrono::seconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
        if (cond()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return cond();
}

}  // namespace cupola::test

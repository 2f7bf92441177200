#pragma once
// Writes a runnable cluster config for tests: the repo's dome-4ch layout with absolute paths to
// the key, scene and show, its own ports and multicast group, and small images.
#include <nlohmann/json.hpp>

#include <string>

#include "support/test_support.hpp"

namespace cupola::test {

inline std::string write_test_cluster(const std::string& dir, int port_base, int width, int height,
                                      const nlohmann::json& overrides = nlohmann::json::object()) {
    nlohmann::json c = nlohmann::json::parse(read_text(source_path("configs/dome-4ch.json")));
    for (const char* k : {"key_file", "scene", "show"}) c[k] = source_path("configs/" + c[k].get<std::string>());
    c["network"]["snapshot_port"] = port_base;
    c["network"]["report_port"] = port_base + 1;
    c["network"]["multicast_group"] = "239.255.77." + std::to_string(port_base % 200 + 1);
    c["network"]["channel_timeout_ms"] = 30000;
    c["network"]["hello_wait_ms"] = 60000;
    c["output"]["width"] = width;
    c["output"]["height"] = height;
    c["output"]["domemaster_size"] = 2 * width;
    c.merge_patch(overrides);
    const std::string path = dir + "/cluster.json";
    write_text(path, c.dump(2));
    return path;
}

}  // namespace cupola::test

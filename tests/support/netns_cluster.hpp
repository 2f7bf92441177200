#pragma once
// A real 4-channel cluster across network namespaces (support/netns_testbed.hpp): a master host,
// three slave hosts (s1 runs channels 0 and 1, s2 channel 2, s3 channel 3), an optional relay
// host between them (tests/tools/fault_relay.cpp: reordering, duplication, delay) and an
// attacker host on the same switch. Multicast crosses the bridge; nothing runs on loopback.
//
// Without the relay every node uses one config (group 239.255.61.1). With it, the master sends to
// 239.255.61.1, the relay forwards to 239.255.61.2 where the slaves listen, and the slaves send
// their reports to the relay, which forwards them to the master.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "image/frame_image.hpp"
#include "support/cluster_fixture.hpp"
#include "support/loopback_run.hpp"
#include "support/netns_testbed.hpp"
#include "util/child_process.hpp"

namespace cupola::test {

struct NetnsClusterOptions {
    int width = 24, height = 24;
    int resend_interval_ms = 20;
    int channel_timeout_ms = 3000;
    int max_datagram_bytes = 1400;
    std::vector<std::string> relay_faults;  // empty: no relay; else e.g. {"--reorder", "0.2"}
};

class NetnsCluster {
public:
    static constexpr int kSnapshotPort = 47500, kReportPort = 47501;
    static constexpr int kChannels = 4;

    NetnsCluster(const std::string& tag, NetnsClusterOptions o)
        : bed(tag, {"master", "relay", "s1", "s2", "s3", "attacker"}),
          opt(std::move(o)),
          dir(scratch_dir("netns_" + tag)) {
        const bool relay = !opt.relay_faults.empty();
        nlohmann::json overrides = {{"frame_rate_hz", 0},
                                    {"output", {{"formats", {"png"}}}},
                                    {"network",
                                     {{"interface_address", "0.0.0.0"},
                                      {"master_address", bed.host("master").address},
                                      {"resend_interval_ms", opt.resend_interval_ms},
                                      {"max_datagram_bytes", opt.max_datagram_bytes}}}};
        master_config = write_test_cluster(dir, kSnapshotPort, opt.width, opt.height, overrides);
        nlohmann::json c = nlohmann::json::parse(read_text(master_config));
        c["key_file"] = dir + "/cluster.key";
        c["network"]["multicast_group"] = "239.255.61.1";
        c["network"]["channel_timeout_ms"] = opt.channel_timeout_ms;
        c["network"]["hello_wait_ms"] = 60000;
        c["network"]["strict_key_permissions"] = true;
        write_text(master_config, c.dump(2));
        // The key, readable by its owner only (strict mode would refuse anything else).
        write_text(dir + "/cluster.key", read_text(source_path("configs/keys/loopback.key")));
        std::filesystem::permissions(dir + "/cluster.key",
                                     std::filesystem::perms::owner_read | std::filesystem::perms::owner_write,
                                     std::filesystem::perm_options::replace);
        slave_config = master_config;
        if (relay) {
            c["network"]["multicast_group"] = "239.255.61.2";
            c["network"]["master_address"] = bed.host("relay").address;
            slave_config = dir + "/cluster-slaves.json";
            write_text(slave_config, c.dump(2));
        }
        for (int id = 0; id < kChannels; ++id) channel_names[id] = c["channels"][id]["name"].get<std::string>();
    }

    ~NetnsCluster() { stop_all(); }

    static std::string host_of(int channel) { return channel <= 1 ? "s1" : channel == 2 ? "s2" : "s3"; }
    std::string out_dir(int channel) const { return dir + "/" + channel_names.at(channel); }
    std::string stats_file(int channel) const { return out_dir(channel) + ".stats.json"; }
    std::string master_stats() const { return dir + "/master.stats.json"; }

    void start_relays() {
        if (opt.relay_faults.empty()) return;
        const std::string relay = bed.host("relay").address;
        auto start = [&](const std::string& name, std::vector<std::string> route) {
            std::vector<std::string> argv = bed.exec_prefix("relay");
            argv.push_back(bin_path("cupola-fault-relay"));
            for (auto& a : route) argv.push_back(a);
            for (auto& a : opt.relay_faults) argv.push_back(a);
            argv.insert(argv.end(), {"--seed", "7", "--stats", dir + "/relay-" + name + ".json"});
            relays.emplace_back(argv, dir + "/relay-" + name + ".log");
        };
        start("snapshots",
              {"--listen", "239.255.61.1:" + std::to_string(kSnapshotPort), "--join", "239.255.61.1", "--iface", relay,
               "--to", "239.255.61.2:" + std::to_string(kSnapshotPort), "--out-iface", relay});
        start("reports", {"--listen", relay + ":" + std::to_string(kReportPort), "--to",
                          bed.host("master").address + ":" + std::to_string(kReportPort), "--out-iface", relay});
        for (const char* n : {"snapshots", "reports"}) {
            const std::string f = dir + "/relay-" + n + ".json";
            if (!wait_until([&] { return std::filesystem::exists(f); }, std::chrono::seconds(20)))
                throw std::runtime_error("relay " + std::string(n) +
                                         " did not start: " + read_text(dir + "/relay-" + n + ".log"));
        }
    }

    ChildProcess start_slave(int channel, const std::string& log_suffix = "") {
        std::vector<std::string> argv = bed.exec_prefix(host_of(channel));
        argv.insert(argv.end(),
                    {bin_path("cupola-slave"), "--config", slave_config, "--channel", std::to_string(channel), "--out",
                     out_dir(channel), "--idle-timeout", "60", "--stats", stats_file(channel)});
        return ChildProcess(argv, out_dir(channel) + log_suffix + ".log", {"DISPLAY", "WAYLAND_DISPLAY"});
    }

    ChildProcess start_master(int frames, const std::string& name = "master") {
        std::vector<std::string> argv = bed.exec_prefix("master");
        argv.insert(argv.end(),
                    {bin_path("cupola-master"), "--config", master_config, "--frames", std::to_string(frames),
                     "--events", dir + "/" + name + ".events.jsonl", "--stats", master_stats()});
        return ChildProcess(argv, dir + "/" + name + ".log", {"DISPLAY", "WAYLAND_DISPLAY"});
    }

    void start_all(int frames) {
        start_relays();
        for (int id = 0; id < kChannels; ++id) slaves.push_back(start_slave(id));
        master.emplace(start_master(frames));
    }

    // Waits for the master and every slave to exit 0 (appends to `failures` otherwise).
    void finish(std::string& failures, std::chrono::seconds limit = std::chrono::seconds(240)) {
        if (master) {
            auto rc = master->wait_for(limit);
            if (rc != 0)
                failures += "master exit " + (rc ? std::to_string(*rc) : "timeout") + ": " +
                            read_text(dir + "/master.log") + "\n";
        }
        for (size_t i = 0; i < slaves.size(); ++i) {
            auto rc = slaves[i].wait_for(std::chrono::seconds(30));
            if (rc != 0)
                failures += "slave " + std::to_string(i) + " exit " + (rc ? std::to_string(*rc) : "timeout") + ": " +
                            read_text(out_dir(static_cast<int>(i)) + ".log") + "\n";
        }
        stop_relays();
    }

    void stop_relays() {
        for (auto& r : relays) {
            r.kill(SIGTERM);
            r.wait_for(std::chrono::seconds(5));
        }
    }

    void stop_all() {
        for (auto& s : slaves) s.kill(SIGKILL);
        if (master) master->kill(SIGKILL);
        for (auto& r : relays) r.kill(SIGKILL);
        for (auto& s : slaves) s.wait_for(std::chrono::seconds(5));
        if (master) master->wait_for(std::chrono::seconds(5));
        for (auto& r : relays) r.wait_for(std::chrono::seconds(5));
    }

    // The snapshot hash of every frame each channel wrote (from the frame files' metadata).
    std::map<int, std::map<uint64_t, std::string>> written_frames() const {
        std::map<int, std::map<uint64_t, std::string>> out;
        for (int id = 0; id < kChannels; ++id) {
            if (!std::filesystem::exists(out_dir(id))) continue;
            for (const auto& e : std::filesystem::directory_iterator(out_dir(id))) {
                if (e.path().extension() != ".png") continue;
                FrameMetadata meta;
                read_image(e.path().string(), &meta);
                out[id][meta.frame] = meta.snapshot_hash;
            }
        }
        return out;
    }

    // Frame -> hash as the master broadcast it (its events file).
    std::map<uint64_t, std::string> master_hashes(const std::string& name = "master") const {
        std::map<uint64_t, std::string> out;
        for (const auto& e : read_events(dir + "/" + name + ".events.jsonl"))
            if (e.value("event", "") == "frame") out[e["frame"].get<uint64_t>()] = e["hash"].get<std::string>();
        return out;
    }

    nlohmann::json stats(const std::string& file) const { return nlohmann::json::parse(read_text(file)); }

    // Waits until the channel has written `frame`.
    bool wait_for_frame(int channel, uint64_t frame, std::chrono::seconds limit = std::chrono::seconds(120)) const {
        const std::string f = out_dir(channel) + "/" + frame_file_name(frame, "png");
        return wait_until([&] { return std::filesystem::exists(f); }, limit);
    }

    // SIGKILLs channel `id`'s slave once it has written frame `at_frame`, starts it again (its log
    // gets `suffix`), and returns the seconds from the restart to the first frame file it wrote (the
    // file's own time, so polling adds nothing); nullopt when a step did not happen in time.
    std::optional<double> kill_and_restart(int id, uint64_t at_frame, const std::string& suffix) {
        auto& slave = slaves.at(static_cast<size_t>(id));
        if (!wait_for_frame(id, at_frame)) return std::nullopt;
        slave.kill(SIGKILL);
        if (!slave.wait_for(std::chrono::seconds(5))) return std::nullopt;
        const auto restarted = std::filesystem::file_time_type::clock::now();
        slave = start_slave(id, suffix);
        std::optional<std::filesystem::file_time_type> first;
        auto rendered_again = [&] {
            for (const auto& e : std::filesystem::directory_iterator(out_dir(id))) {
                std::error_code ec;
                const auto t = std::filesystem::last_write_time(e.path(), ec);
                if (!ec && e.path().extension() == ".png" && t > restarted && (!first || t < *first)) first = t;
            }
            return first.has_value();
        };
        if (!wait_until(rendered_again, std::chrono::seconds(60))) return std::nullopt;
        return std::chrono::duration<double>(*first - restarted).count();
    }

    NetnsTestbed bed;
    NetnsClusterOptions opt;
    std::string dir, master_config, slave_config;
    std::map<int, std::string> channel_names;
    std::vector<ChildProcess> relays;
    std::vector<ChildProcess> slaves;
    std::optional<ChildProcess> master;
};

}  // namespace cupola::test

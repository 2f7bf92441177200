// libFuzzer target cupola-fuzz-config: the cluster-config reader (load_cluster_config, with the
// JsonReader and the compiled-in schema it takes defaults and ranges from) under hostile input.
// Each input is written as a cluster config into a private directory that also holds the files
// the shipped configs name (keys/loopback.key, scenes/*.json, shows/*.json; empty: the cluster
// reader only checks that they exist), so seeds from configs/ get past the file checks.
// Checked invariants (a violation prints what failed and aborts, which libFuzzer reports):
//   * the reader returns a config or throws ConfigError; any other exception is a bug;
//   * a returned config keeps the rules the reader promises: at least one channel, unique
//     channel ids and names, snapshot_port != report_port, min_exposure <= max_exposure.
// ASan/UBSan (with -fno-sanitize-recover=all) turn memory errors and UB into crashes.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "config/cluster_config.hpp"
#include "config/config_error.hpp"

using namespace cupola;
namespace fs = std::filesystem;

namespace {

[[noreturn]] void violated(const char* what) {
    std::fprintf(stderr, "cupola-fuzz-config: %s\n", what);
    std::abort();
}

const std::string& work_dir() {
    static const std::string dir = [] {
        char name[] = "/tmp/cupola-fuzz-config-XXXXXX";
        if (!mkdtemp(name)) violated("cannot make a scratch directory");
        for (const char* f : {"keys/loopback.key", "scenes/earth-moon.json", "scenes/earth-physical.json",
                              "shows/earth-moon.json", "shows/descent-sunset.json", "shows/eclipse-2006-ground.json"}) {
            fs::create_directories(fs::path(name) / fs::path(f).parent_path());
            std::ofstream(fs::path(name) / f) << "{}";
        }
        return std::string(name);
    }();
    return dir;
}

void check(const ClusterConfig& c) {
    if (c.channels.empty()) violated("a config without channels was accepted");
    std::set<int> ids;
    std::set<std::string> names;
    for (const auto& ch : c.channels) {
        if (!ids.insert(ch.id).second) violated("a duplicate channel id was accepted");
        if (!names.insert(ch.name).second) violated("a duplicate channel name was accepted");
        if (ch.width < 8 || ch.height < 8) violated("a channel smaller than 8 pixels was accepted");
    }
    if (c.network.snapshot_port == c.network.report_port) violated("equal ports were accepted");
    if (c.output.auto_exposure.min_exposure > c.output.auto_exposure.max_exposure)
        violated("min_exposure > max_exposure was accepted");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string file = work_dir() + "/cluster.json";
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        check(load_cluster_config(file));
    } catch (const ConfigError&) {
        // rejected, naming file and field: fine
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cupola-fuzz-config: not a ConfigError: %s\n", e.what());
        std::abort();
    }
    return 0;
}

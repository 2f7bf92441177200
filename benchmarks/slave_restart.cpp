// Benchmark (not a test): how soon a killed slave renders again after it is started anew, on the
// 4-channel cluster across network namespaces (tests/support/netns_cluster.hpp; needs root).
// Channel 3's slave is SIGKILLed and restarted --restarts times during one run; for each restart:
// the seconds from the spawn to its first frame file (the file's time), and the slave's own
// "ready to join" (from main to the renderer built). The bare start of the program
// (`cupola-slave --help`: the dynamic loader and the libraries' initialisers) is timed alone, as
// the part of the start-up that Cupola's code does not control. The bound is 1 s.
//   build/bin/slave_restart [--restarts 6] [--size 24]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <regex>

#include "support/netns_cluster.hpp"

using namespace cupola;

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The "ready to join N ms" a slave logged, or -1.
double ready_to_join_ms(const std::string& log) {
    std::smatch m;
    const std::string text = test::read_text(log);
    static const std::regex re("ready to join ([0-9]+) ms");
    return std::regex_search(text, m, re) ? std::stod(m[1].str()) : -1.0;
}

// Wall seconds of `cupola-slave --help`, the median of n runs.
double bare_start_s(int n) {
    std::vector<double> s;
    for (int i = 0; i < n; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        ChildProcess p({test::bin_path("cupola-slave"), "--help"}, "/dev/null");
        p.wait_for(std::chrono::seconds(30));
        s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return median(s);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Cupola: a killed slave's first frame after its restart (4-channel cluster, network namespaces)"};
    int restarts = 6, size = 24;
    app.add_option("--restarts", restarts)->check(CLI::Range(1, 50));
    app.add_option("--size", size, "channel width and height in pixels")->check(CLI::Range(8, 4096));
    CLI11_PARSE(app, argc, argv);
    const std::string why = test::NetnsTestbed::unavailable_reason();
    if (!why.empty()) {
        std::fprintf(stderr, "slave_restart: needs network namespaces: %s\n", why.c_str());
        return 2;
    }
    test::NetnsClusterOptions o;
    o.width = o.height = size;
    test::NetnsCluster c("restart", o);
    c.start_all(100 + 60 * restarts);
    std::vector<double> first_s, ready_ms;
    std::printf("| restart | first frame after the spawn, s | ready to join (from main), ms |\n|---|---|---|\n");
    for (int k = 0; k < restarts; ++k) {
        const std::string suffix = "-restart" + std::to_string(k);
        const auto s = c.kill_and_restart(3, 40 + 60 * static_cast<uint64_t>(k), suffix);
        if (!s) {
            std::fprintf(stderr, "slave_restart: restart %d did not render again\n", k);
            return 1;
        }
        first_s.push_back(*s);
        ready_ms.push_back(ready_to_join_ms(c.out_dir(3) + suffix + ".log"));
        std::printf("| %d | %.3f | %.0f |\n", k + 1, *s, ready_ms.back());
        std::fflush(stdout);
    }
    std::string failures;
    c.finish(failures, std::chrono::seconds(600));
    const double bare = bare_start_s(5);
    std::printf("\nfirst frame: min %.3f s, median %.3f s, max %.3f s (bound 1 s: median %s)\n",
                *std::min_element(first_s.begin(), first_s.end()), median(first_s),
                *std::max_element(first_s.begin(), first_s.end()), median(first_s) < 1.0 ? "within" : "OVER");
    std::printf("ready to join from main: median %.0f ms; bare program start (--help): median %.3f s\n",
                median(ready_ms), bare);
    if (!failures.empty()) std::fprintf(stderr, "%s\n", failures.c_str());
    return failures.empty() ? 0 : 1;
}

// cupola-atmosphere-reference: evaluates the CPU reference integrator on the fixed validation set
// (common/atmosphere/validation_set.hpp) and writes the reference dataset CSV that the production
// atmosphere models are measured against (format: common/atmosphere/reference_dataset.hpp).
//   cupola-atmosphere-reference --body earth|mars --out FILE.csv [--directions N] [--orders N]
//                               [--paths N] [--seed S] [--threads N] [--limit N]
// The output is independent of --threads: every query is deterministic for the seed and rows are
// written in validation-set order. The file is written to FILE.csv.tmp and renamed at the end.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "atmosphere/atmosphere_parameters.hpp"
#include "atmosphere/reference_dataset.hpp"
#include "atmosphere/reference_integrator.hpp"
#include "atmosphere/validation_set.hpp"
#include "util/cli_main.hpp"

namespace at = cupola::atmosphere;
namespace fs = std::filesystem;

namespace {

std::string command_line(int argc, char** argv) {
    std::string s;
    for (int i = 0; i < argc; ++i) {
        const std::string a = argv[i];
        if (i) s += ' ';
        s += a.find_first_of(" \t'\"") == std::string::npos ? a : "'" + a + "'";
    }
    return s;
}

std::string utc_now() {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

// Evaluates every case on `threads` workers; rows come back in case order.
std::vector<at::ReferenceRow> evaluate(const at::ReferenceIntegrator& ri, const std::vector<at::ValidationCase>& cases,
                                       int threads) {
    const std::size_t total = cases.size();
    std::vector<at::ReferenceRow> rows(total);
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex mutex;  // guards error and the progress report
    std::size_t reported_twentieths = 0;
    const auto start = std::chrono::steady_clock::now();

    auto worker = [&] {
        for (std::size_t i; !failed && (i = next++) < total;) {
            try {
                const at::SkyRadiance s = ri.sky(cases[i].query);
                if (!std::isfinite(s.luminance) || !std::isfinite(s.multiple_luminance_stderr))
                    throw std::runtime_error("non-finite radiance for case " + std::to_string(i));
                rows[i] = at::make_reference_row(cases[i], s);
            } catch (...) {
                std::lock_guard lock(mutex);
                if (!error) error = std::current_exception();
                failed = true;
                return;
            }
            const std::size_t n = ++done;
            std::lock_guard lock(mutex);
            if (n * 20 / total > reported_twentieths || n == total) {
                reported_twentieths = n * 20 / total;
                const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                spdlog::info("{}/{} queries ({:.0f} %), {:.0f} s elapsed, ~{:.0f} s left", n, total, 100.0 * n / total,
                             elapsed, elapsed * (total - n) / n);
            }
        }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
    return rows;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"cupola-atmosphere-reference: the CPU reference sky radiance on the validation set, as CSV"};
    std::string body = "earth", out;
    int directions = 512, orders = 6, paths = 4096, limit = -1;
    std::uint64_t seed = 1;
    int threads = std::max(1u, std::thread::hardware_concurrency());
    bool verbose = false;
    app.add_option("--body", body, "atmosphere preset")->check(CLI::IsMember({"earth", "mars"}));
    app.add_option("-o,--out", out, "output CSV file")->required();
    app.add_option("--directions", directions, "view directions per (camera, sun) set")->check(CLI::Range(1, 1000000));
    app.add_option("--orders", orders, "scattering orders")->check(CLI::Range(1, 100));
    app.add_option("--paths", paths, "Monte Carlo paths per query")->check(CLI::Range(0, 100000000));
    app.add_option("--seed", seed, "Monte Carlo seed (the same for every query)");
    app.add_option("--threads", threads, "worker threads (the output does not depend on it)")
        ->check(CLI::Range(1, 1024));
    app.add_option("--limit", limit, "write only the first N rows (for tests)")->check(CLI::Range(0, 100000000));
    app.add_flag("-v,--verbose", verbose, "debug logging");
    CLI11_PARSE(app, argc, argv);
    cupola::setup_logging("atmosphere-reference", verbose, false);
    return cupola::run_main("cupola-atmosphere-reference", [&] {
        const at::AtmosphereParameters params =
            body == "earth" ? at::AtmosphereParameters::earth() : at::AtmosphereParameters::mars();
        at::ReferenceSettings settings;
        settings.scattering_orders = orders;
        settings.ms_paths = paths;
        settings.seed = seed;
        const at::ReferenceIntegrator ri(params, settings);

        std::vector<at::ValidationCase> cases = at::validation_set(params, directions);
        if (limit >= 0 && static_cast<std::size_t>(limit) < cases.size()) cases.resize(limit);
        spdlog::info("{}: {} queries, {} orders, {} paths, seed {}, {} thread(s)", body, cases.size(), orders, paths,
                     seed, threads);

        const auto start = std::chrono::steady_clock::now();
        at::ReferenceDataset d;
        d.preset = body;
        d.hash = params.hash_hex();
        d.orders = orders;
        d.paths = paths;
        d.seed = seed;
        d.directions = directions;
        const auto& wl = settings.wavelengths_nm;
        d.metadata = {{"panel_height_m", fmt::format("{}", settings.panel_height_m)},
                      {"ms_panel_height_m", fmt::format("{}", settings.ms_panel_height_m)},
                      {"wavelengths_nm", fmt::format("{}..{} ({})", wl.front(), wl.back(), wl.size())},
                      {"rows", std::to_string(cases.size())},
                      {"command", command_line(argc, argv)},
                      {"date", utc_now()}};
        d.rows = evaluate(ri, cases, threads);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

        const fs::path path(out), tmp(out + ".tmp");
        if (path.has_parent_path()) fs::create_directories(path.parent_path());
        {
            std::ofstream f(tmp);
            if (!f) throw std::runtime_error("cannot write " + tmp.string());
            write_reference_dataset(
                f, d,
                {"Cupola atmosphere reference dataset: ReferenceIntegrator::sky() on validation_set() "
                 "(common/atmosphere/validation_set.hpp); format in common/atmosphere/reference_dataset.hpp.",
                 "luminance and luminance_stderr (Monte Carlo part, orders >= 2) in cd/m^2; r,g,b linear sRGB "
                 "(D65) and x,y,z CIE 1931, photometric scale (y = luminance).",
                 "ReferenceSettings: scattering_orders=orders, ms_paths=paths, seed=seed, everything else at its "
                 "default (recorded below)."});
            f.close();
            if (!f) throw std::runtime_error("error writing " + tmp.string());
        }
        fs::rename(tmp, path);
        spdlog::info("wrote {} rows to {} in {:.1f} s", d.rows.size(), out, seconds);
        return 0;
    });
}

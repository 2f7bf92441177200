// cupola-atmosphere-reference: evaluates the CPU reference integrator on the fixed validation set
// (common/atmosphere/validation_set.hpp) and writes the reference dataset CSV that the production
// atmosphere models are measured against (format: common/atmosphere/reference_dataset.hpp).
//   cupola-atmosphere-reference --body earth|mars --out FILE.csv [--directions N] [--orders N]
//                               [--paths N] [--seed S] [--estimator lit_segment|collision]
//                               [--max-paths N --target-noise F [--target-floor L]]
//                               [--suns Z,Z --keep OLD.csv] [--threads N] [--limit N]
// The output is independent of --threads: every query is deterministic for the seed and rows are
// written in validation-set order. The file is written to FILE.csv.tmp and renamed at the end.
// --suns recomputes only the rows at those sun zenith angles and copies the others from --keep
// (which must hold the same validation set); the file's metadata then records both settings
// (common/atmosphere/reference_dataset.hpp, row_settings()).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <algorithm>
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
    if (total == 0) return {};
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

struct Options {
    std::string body = "earth", out, estimator = "lit_segment", keep;
    int directions = 512, orders = 6, paths = 4096, max_paths = 0, limit = -1;
    double target_noise = 0.0, target_floor = 0.0;
    std::vector<double> suns;
    std::uint64_t seed = 1;
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    bool verbose = false;
};

at::ReferenceSettings settings_of(const Options& o) {
    at::ReferenceSettings settings;
    settings.scattering_orders = o.orders;
    settings.ms_paths = o.paths;
    settings.seed = o.seed;
    settings.ms_estimator = o.estimator == "collision" ? at::MsEstimator::kCollision : at::MsEstimator::kLitSegment;
    settings.ms_max_paths = o.max_paths;
    settings.ms_target_noise = o.target_noise;
    settings.ms_target_floor = o.target_floor;
    return settings;
}

bool selected(const Options& o, const at::ValidationCase& c) {
    return o.suns.empty() || std::find(o.suns.begin(), o.suns.end(), c.query.sun_zenith_deg) != o.suns.end();
}

// The rows of --keep that are not recomputed, checked against the validation set; their settings
// (which must be the same for every kept sun zenith) go into the metadata with a "kept_" prefix.
void take_kept_rows(const Options& o, const std::vector<at::ValidationCase>& cases, const std::string& hash,
                    at::ReferenceDataset& d) {
    const at::ReferenceDataset kept = at::read_reference_dataset(o.keep);
    if (kept.hash != hash) throw std::runtime_error(o.keep + ": made for another preset (hash " + kept.hash + ")");
    if (kept.rows.size() < cases.size())
        throw std::runtime_error(o.keep + ": " + std::to_string(kept.rows.size()) + " rows, need " +
                                 std::to_string(cases.size()));
    std::string kept_key;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const at::ReferenceRow& r = kept.rows[i];
        const at::SkyQuery &a = r.c.query, &b = cases[i].query;
        if (r.c.camera != cases[i].camera || a.altitude_m != b.altitude_m || a.view_zenith_deg != b.view_zenith_deg ||
            a.sun_zenith_deg != b.sun_zenith_deg || a.relative_azimuth_deg != b.relative_azimuth_deg)
            throw std::runtime_error(o.keep + ": row " + std::to_string(i) + " is not validation case " +
                                     std::to_string(i));
        if (selected(o, cases[i])) continue;
        d.rows[i] = r;
        const at::ReferenceSettings s = at::row_settings(kept, a.sun_zenith_deg);
        const std::string key =
            fmt::format("{} {} {} {} {} {} {}", s.scattering_orders, s.ms_paths, s.seed,
                        static_cast<int>(s.ms_estimator), s.ms_max_paths, s.ms_target_noise, s.ms_target_floor);
        if (!kept_key.empty() && key != kept_key)
            throw std::runtime_error(o.keep + ": the kept rows were made with different settings");
        kept_key = key;
        d.metadata["kept_orders"] = std::to_string(s.scattering_orders);
        d.metadata["kept_paths"] = std::to_string(s.ms_paths);
        d.metadata["kept_seed"] = std::to_string(s.seed);
        d.metadata["kept_ms_estimator"] = s.ms_estimator == at::MsEstimator::kCollision ? "collision" : "lit_segment";
        d.metadata["kept_ms_max_paths"] = std::to_string(s.ms_max_paths);
        d.metadata["kept_ms_target_noise"] = fmt::format("{}", s.ms_target_noise);
        d.metadata["kept_ms_target_floor"] = fmt::format("{}", s.ms_target_floor);
    }
    for (const char* key : {"date", "command"})
        if (kept.metadata.count(key)) d.metadata[std::string("kept_") + key] = kept.metadata.at(key);
}

void add_metadata(const Options& o, const at::ReferenceSettings& settings, std::size_t rows, const std::string& command,
                  at::ReferenceDataset& d) {
    const auto& wl = settings.wavelengths_nm;
    d.metadata["panel_height_m"] = fmt::format("{}", settings.panel_height_m);
    d.metadata["ms_panel_height_m"] = fmt::format("{}", settings.ms_panel_height_m);
    d.metadata["wavelengths_nm"] = fmt::format("{}..{} ({})", wl.front(), wl.back(), wl.size());
    d.metadata["rows"] = std::to_string(rows);
    d.metadata["command"] = command;
    d.metadata["date"] = utc_now();
    d.metadata["ms_estimator"] = o.estimator;
    d.metadata["ms_max_paths"] = std::to_string(o.max_paths);
    d.metadata["ms_target_noise"] = fmt::format("{}", o.target_noise);
    d.metadata["ms_target_floor"] = fmt::format("{}", o.target_floor);
    if (!o.suns.empty()) {
        std::string list;
        for (double z : o.suns) list += (list.empty() ? "" : ",") + fmt::format("{}", z);
        d.metadata["recomputed_sun_zenith_deg"] = list;
    }
}

void write_dataset(const std::string& out, const at::ReferenceDataset& d) {
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
             "ReferenceSettings per row: row_settings() in common/atmosphere/reference_dataset.hpp (orders, paths, "
             "seed and the ms_* keys below; kept_* for rows copied from an earlier file), everything else at its "
             "default (recorded below)."});
        f.close();
        if (!f) throw std::runtime_error("error writing " + tmp.string());
    }
    fs::rename(tmp, path);
}

int generate(const Options& o, const std::string& command) {
    const at::AtmosphereParameters params =
        o.body == "earth" ? at::AtmosphereParameters::earth() : at::AtmosphereParameters::mars();
    const at::ReferenceSettings settings = settings_of(o);
    const at::ReferenceIntegrator ri(params, settings);
    std::vector<at::ValidationCase> cases = at::validation_set(params, o.directions);
    if (o.limit >= 0 && static_cast<std::size_t>(o.limit) < cases.size()) cases.resize(o.limit);
    std::vector<at::ValidationCase> todo;
    std::vector<std::size_t> index;
    for (std::size_t i = 0; i < cases.size(); ++i)
        if (selected(o, cases[i])) {
            todo.push_back(cases[i]);
            index.push_back(i);
        }
    spdlog::info("{}: {} of {} queries, {} orders, {} paths (adaptive up to {}, target {}), {}, seed {}, {} thread(s)",
                 o.body, todo.size(), cases.size(), o.orders, o.paths, o.max_paths, o.target_noise, o.estimator, o.seed,
                 o.threads);
    const auto start = std::chrono::steady_clock::now();
    at::ReferenceDataset d;
    d.preset = o.body;
    d.hash = params.hash_hex();
    d.orders = o.orders;
    d.paths = o.paths;
    d.seed = o.seed;
    d.directions = o.directions;
    d.rows.resize(cases.size());
    if (!o.suns.empty()) take_kept_rows(o, cases, d.hash, d);
    add_metadata(o, settings, cases.size(), command, d);
    const std::vector<at::ReferenceRow> computed = evaluate(ri, todo, o.threads);
    for (std::size_t j = 0; j < computed.size(); ++j) d.rows[index[j]] = computed[j];
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_dataset(o.out, d);
    spdlog::info("wrote {} rows ({} computed) to {} in {:.1f} s", d.rows.size(), todo.size(), o.out, seconds);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"cupola-atmosphere-reference: the CPU reference sky radiance on the validation set, as CSV"};
    Options o;
    app.add_option("--body", o.body, "atmosphere preset")->check(CLI::IsMember({"earth", "mars"}));
    app.add_option("-o,--out", o.out, "output CSV file")->required();
    app.add_option("--directions", o.directions, "view directions per (camera, sun) set")
        ->check(CLI::Range(1, 1000000));
    app.add_option("--orders", o.orders, "scattering orders")->check(CLI::Range(1, 100));
    app.add_option("--paths", o.paths, "Monte Carlo paths per query (the first batch if adaptive)")
        ->check(CLI::Range(0, 100000000));
    app.add_option("--estimator", o.estimator, "how orders >= 2 collect sunlight")
        ->check(CLI::IsMember({"lit_segment", "collision"}));
    app.add_option("--max-paths", o.max_paths, "adaptive: double the paths up to this many")
        ->check(CLI::Range(0, 100000000));
    app.add_option("--target-noise", o.target_noise, "adaptive: stop at this relative standard error")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--target-floor", o.target_floor, "adaptive: ... relative to at least this luminance (cd/m^2)")
        ->check(CLI::Range(0.0, 1e9));
    app.add_option("--suns", o.suns, "recompute only these sun zenith angles (deg); the rest from --keep")
        ->delimiter(',');
    app.add_option("--keep", o.keep, "dataset the rows not recomputed are copied from");
    app.add_option("--seed", o.seed, "Monte Carlo seed (the same for every query)");
    app.add_option("--threads", o.threads, "worker threads (the output does not depend on it)")
        ->check(CLI::Range(1, 1024));
    app.add_option("--limit", o.limit, "write only the first N rows (for tests)")->check(CLI::Range(0, 100000000));
    app.add_flag("-v,--verbose", o.verbose, "debug logging");
    CLI11_PARSE(app, argc, argv);
    cupola::setup_logging("atmosphere-reference", o.verbose, false);
    if (o.suns.empty() != o.keep.empty()) {
        std::fprintf(stderr, "cupola-atmosphere-reference: --suns and --keep go together\n");
        return 2;
    }
    const std::string command = command_line(argc, argv);
    return cupola::run_main("cupola-atmosphere-reference", [&] { return generate(o, command); });
}

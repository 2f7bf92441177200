// cupola-atmosphere-accuracy: the error of a production atmosphere level against the stored
// reference dataset, per validation group (camera x Sun zenith) and overall, as a Markdown table.
//   cupola-atmosphere-accuracy [--model LEVEL] [--dataset FILE]
//   cupola-atmosphere-accuracy [--model LEVEL] --live-orders N --live-directions K
// The second form computes the reference on the spot instead (N scattering orders, K directions
// per validation group; N = 1 needs no Monte Carlo): it separates the model's errors by order.
// The statistics are those of common/atmosphere/production_accuracy.hpp (what the tests check).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

#include "atmosphere/production_accuracy.hpp"
#include "atmosphere/validation_set.hpp"
#include "util/cli_main.hpp"
#include "util/cli_parse.hpp"

namespace {
namespace at = cupola::atmosphere;

void print_row(const at::ErrorStats& g) {
    const std::string sun = g.sun_zenith_deg < 0 ? "" : std::to_string(static_cast<int>(g.sun_zenith_deg));
    std::printf("| %s | %s | %d | %d | %.2f %% | %.1f %% | %+.2f %% | %.4f | %.4f | %.2f %% |\n", g.camera.c_str(),
                sun.c_str(), g.used, g.reference_limited, 100 * g.median, 100 * g.p99, 100 * g.mean_signed,
                g.chroma_median, g.chroma_p99, 100 * g.reference_noise_median);
}
at::ReferenceDataset live_dataset(int orders, int directions) {
    at::ReferenceSettings settings;
    settings.scattering_orders = orders;
    const at::AtmosphereParameters p = at::AtmosphereParameters::earth();
    const at::ReferenceIntegrator reference(p, settings);
    at::ReferenceDataset d;
    for (const at::ValidationCase& c : at::validation_set(p, directions))
        d.rows.push_back(at::make_reference_row(c, reference.sky(c.query)));
    return d;
}
}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"cupola-atmosphere-accuracy: a production atmosphere level against the reference dataset"};
    std::string model = at::kDefaultProductionQuality;
    std::string dataset = std::string(CUPOLA_SOURCE_DIR) + "/data/atmosphere/earth_reference.csv";
    app.add_option("--model", model, "production quality level");
    app.add_option("--dataset", dataset, "reference dataset (CSV)");
    int live_orders = 0, live_directions = 32;
    app.add_option("--live-orders", live_orders, "compute the reference now with this many orders")
        ->check(CLI::Range(1, 50));
    app.add_option("--live-directions", live_directions, "directions per group of the live reference")
        ->check(CLI::Range(1, 4096));
    if (const auto stop = cupola::parse_command_line(app, argc, argv, "cupola-atmosphere-accuracy")) return *stop;
    return cupola::run_main("cupola-atmosphere-accuracy", [&]() -> int {
        cupola::setup_logging("cupola-atmosphere-accuracy", false, true);
        const at::ReferenceDataset ref =
            live_orders > 0 ? live_dataset(live_orders, live_directions) : at::read_reference_dataset(dataset);
        if (live_orders > 0) dataset = "a live reference of " + std::to_string(live_orders) + " orders";
        const at::ProductionAtmosphere m(at::AtmosphereParameters::earth(), at::production_quality(model));
        const at::AccuracyReport r = at::measure_accuracy(m, ref);
        std::printf("model %s against %s\n\n", model.c_str(), dataset.c_str());
        std::printf("| camera | sun° | n | limited | median | p99 | bias | Δu′v′ median | Δu′v′ p99 | ref. noise |\n");
        std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
        for (const auto& g : r.groups) print_row(g);
        print_row(r.overall);
        return 0;
    });
}

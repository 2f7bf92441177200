// cupola-atmosphere-accuracy: the error of a production atmosphere level against the stored
// reference dataset, per validation group (camera x Sun zenith) and overall, as a Markdown table.
//   cupola-atmosphere-accuracy [--model LEVEL] [--dataset FILE]
//   cupola-atmosphere-accuracy [--model LEVEL] --live-orders N --live-directions K
//   ... [--sky-view WxHxS] [--single] [--rows FILE]
// The second form computes the reference on the spot instead (N scattering orders, K directions
// per validation group; N = 1 needs no Monte Carlo): it separates the model's errors by order.
// --sky-view overrides the level's sky-view table size and steps (--sky-view-wavelengths: its
// sample wavelengths), --single turns its multiple
// scattering off, --rows writes every row's reference and model values (CSV) for a closer look.
// The statistics are those of common/atmosphere/production_accuracy.hpp (what the tests check).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <stdexcept>
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
// "WxHxS" -> the quality's sky-view width, height and steps per texel.
void set_sky_view(at::ProductionQuality& q, const std::string& spec) {
    int w = 0, h = 0, s = 0;
    if (std::sscanf(spec.c_str(), "%dx%dx%d", &w, &h, &s) != 3 || w < 2 || h < 4 || h % 2 != 0 || s < 1)
        throw std::invalid_argument("--sky-view '" + spec + "': expected WxHxS (W >= 2, H >= 4 even, S >= 1)");
    q.sky_view = true;
    q.sky_view_width = w;
    q.sky_view_height = h;
    q.sky_view_samples = s;
}

void write_rows(const std::string& path, const at::ProductionAtmosphere& m, const at::ReferenceDataset& ref) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error("--rows: cannot write '" + path + "'");
    f << "camera,sun_zenith_deg,view_zenith_deg,azimuth_deg,hits_ground,ref_y,ref_stderr,model_y,ref_u,ref_v,"
         "model_u,model_v\n";
    for (const at::ReferenceRow& row : ref.rows) {
        const at::ProductionRadiance p = m.sky(row.c.query);
        const glm::dvec2 ur = at::chromaticity_uv(row.xyz), um = at::chromaticity_uv(p.xyz);
        const auto& q = row.c.query;
        f << row.c.camera << ',' << q.sun_zenith_deg << ',' << q.view_zenith_deg << ',' << q.relative_azimuth_deg << ','
          << row.hits_ground << ',' << row.luminance << ',' << row.luminance_stderr << ',' << p.luminance << ',' << ur.x
          << ',' << ur.y << ',' << um.x << ',' << um.y << '\n';
    }
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
    std::string sky_view, rows;
    bool single = false;
    app.add_option("--sky-view", sky_view, "override the sky-view table: WxHxS (width, height, steps)");
    int wavelengths = 0;
    app.add_option("--sky-view-wavelengths", wavelengths, "sample wavelengths of the sky-view march (3 or 6)")
        ->check(CLI::IsMember({3, 6}));
    app.add_flag("--single", single, "turn the model's multiple scattering off");
    app.add_option("--rows", rows, "write every row's reference and model values to this CSV file");
    if (const auto stop = cupola::parse_command_line(app, argc, argv, "cupola-atmosphere-accuracy")) return *stop;
    return cupola::run_main("cupola-atmosphere-accuracy", [&]() -> int {
        cupola::setup_logging("cupola-atmosphere-accuracy", false, true);
        const at::ReferenceDataset ref =
            live_orders > 0 ? live_dataset(live_orders, live_directions) : at::read_reference_dataset(dataset);
        if (live_orders > 0) dataset = "a live reference of " + std::to_string(live_orders) + " orders";
        at::ProductionQuality quality = at::production_quality(model);
        if (!sky_view.empty()) set_sky_view(quality, sky_view);
        if (wavelengths > 0) quality.sky_view_wavelengths = wavelengths;
        if (single) quality.multiple_scattering = false;
        const at::ProductionAtmosphere m(at::AtmosphereParameters::earth(), quality);
        if (!rows.empty()) write_rows(rows, m, ref);
        const at::AccuracyReport r = at::measure_accuracy(m, ref);
        std::printf("model %s against %s\n\n", model.c_str(), dataset.c_str());
        std::printf("| camera | sun° | n | limited | median | p99 | bias | Δu′v′ median | Δu′v′ p99 | ref. noise |\n");
        std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
        for (const auto& g : r.groups) print_row(g);
        print_row(r.overall);
        return 0;
    });
}

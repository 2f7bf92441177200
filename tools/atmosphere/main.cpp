// cupola-atmosphere: sky radiance of a scene's atmosphere from the reference integrator and from
// the production model, for scripts and for checking by hand.
//   cupola-atmosphere --scene FILE --body NAME [--model LEVEL] [ALT VZ SZ AZ]
// Without the four numbers, reads one query per line on stdin:
//   altitude_m view_zenith_deg sun_zenith_deg relative_azimuth_deg
// and prints one JSON object per query line:
//   {"reference": {"rgb": [r,g,b], "luminance": Y}, "production": {...}, "units": "..."}
// Blank lines and lines starting with '#' are skipped. A malformed line prints
// {"error": "...", "line": N} and the run continues; the exit status is then 2.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/cli_parse.hpp"
#include "atmosphere/production_model.hpp"
#include "atmosphere/reference_integrator.hpp"
#include "config/scene_config.hpp"
#include "util/cli_main.hpp"

namespace {
constexpr const char* kUnits =
    "linear sRGB (D65) radiance on a photometric scale: luminance = 0.2126 R + 0.7152 G + 0.0722 B in cd/m^2 "
    "(683 lm/W x CIE 1931 Y); sun = 5772 K black body at the body's distance, point source, disc excluded";

nlohmann::json color_json(const glm::dvec3& rgb, double luminance) {
    return {{"rgb", {rgb.r, rgb.g, rgb.b}}, {"luminance", luminance}};
}

bool parse_query(const std::string& line, cupola::atmosphere::SkyQuery& q, std::string& why) {
    std::istringstream in(line);
    double v[4];
    for (int i = 0; i < 4; ++i)
        if (!(in >> v[i])) {
            why = "expected 4 numbers: altitude_m view_zenith_deg sun_zenith_deg relative_azimuth_deg";
            return false;
        }
    std::string extra;
    if (in >> extra) {
        why = "unexpected text after 4 numbers: '" + extra + "'";
        return false;
    }
    for (double x : v)
        if (!std::isfinite(x)) {
            why = "non-finite number";
            return false;
        }
    if (v[0] < 0.0) {
        why = "altitude_m must be >= 0";
        return false;
    }
    if (v[1] < 0.0 || v[1] > 180.0 || v[2] < 0.0 || v[2] > 180.0) {
        why = "zenith angles must lie in [0, 180] degrees";
        return false;
    }
    q = {v[0], v[1], v[2], v[3]};
    return true;
}
}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"cupola-atmosphere: reference and production sky radiance of a scene's atmosphere"};
    std::string scene_file, body_name, model;
    std::vector<double> query;
    int orders = 4, paths = 4096;
    std::string cache_dir;
    bool verbose = false;
    app.add_option("--scene", scene_file, "scene file (JSON)")->required()->check(CLI::ExistingFile);
    app.add_option("--body", body_name, "body whose atmosphere is probed")->required();
    app.add_option("--model", model, "production quality level (default: the scene's)");
    app.add_option("--orders", orders, "reference scattering orders")->check(CLI::Range(1, 50));
    app.add_option("--paths", paths, "reference Monte Carlo paths per query")->check(CLI::Range(1, 10000000));
    app.add_option("--cache-dir", cache_dir, "atmosphere table cache directory");
    app.add_option("query", query, "altitude_m view_zenith_deg sun_zenith_deg relative_azimuth_deg")->expected(0, 4);
    app.add_flag("-v,--verbose", verbose, "log table building");
    if (const auto stop = cupola::parse_command_line(app, argc, argv, "cupola-atmosphere")) return *stop;
    return cupola::run_main("cupola-atmosphere", [&]() -> int {
        cupola::setup_logging("cupola-atmosphere", verbose, !verbose);
        const cupola::SceneConfig scene = cupola::load_scene_config(scene_file);
        const cupola::BodyConfig* body = scene.find(body_name);
        if (!body) throw std::invalid_argument(scene_file + ": no body named '" + body_name + "'");
        if (!body->atmosphere.present)
            throw std::invalid_argument(scene_file + ": body '" + body_name + "' has no atmosphere");
        if (!query.empty() && query.size() != 4)
            throw std::invalid_argument("give all 4 query numbers or none (then queries come from stdin)");
        namespace atm = cupola::atmosphere;
        atm::TableCacheOptions cache;
        cache.directory = cache_dir;
        const atm::ProductionAtmosphere production(
            body->atmosphere.parameters, atm::production_quality(model.empty() ? body->atmosphere.model : model),
            cache);
        atm::ReferenceSettings settings;
        settings.scattering_orders = orders;
        settings.ms_paths = paths;
        const atm::ReferenceIntegrator reference(body->atmosphere.parameters, settings);

        auto answer = [&](const atm::SkyQuery& q) {
            const atm::SkyRadiance ref = reference.sky(q);
            const atm::ProductionRadiance prod = production.sky(q);
            nlohmann::json j = {{"reference", color_json(ref.rgb, ref.luminance)},
                                {"production", color_json(prod.rgb, prod.luminance)},
                                {"units", kUnits}};
            std::cout << j.dump() << std::endl;
        };
        std::string why;
        if (!query.empty()) {
            atm::SkyQuery q;
            std::ostringstream line;
            line << query[0] << " " << query[1] << " " << query[2] << " " << query[3];
            if (!parse_query(line.str(), q, why)) throw std::invalid_argument(why);
            answer(q);
            return 0;
        }
        int status = 0;
        std::string line;
        for (long n = 1; std::getline(std::cin, line); ++n) {
            const auto first = line.find_first_not_of(" \t\r");
            if (first == std::string::npos || line[first] == '#') continue;
            atm::SkyQuery q;
            if (!parse_query(line, q, why)) {
                std::cout << nlohmann::json{{"error", why}, {"line", n}}.dump() << std::endl;
                status = 2;
                continue;
            }
            answer(q);
        }
        return status;
    });
}

// cupola-sky: apparent positions and eclipse predictions from Cupola's ephemeris, for scripts and
// for checking by hand.
//   cupola-sky [QUERY...]
// With a query as arguments it answers that one; otherwise it reads one query per line on stdin.
// Queries (TIME is ISO 8601 UTC, e.g. 2006-03-29T10:11:00Z):
//   position BODY TIME  -> {"ra_deg", "dec_deg", "distance_km"}   apparent geocentric, of date
//   eclipse TIME        -> {"lat_deg", "lon_deg", "type", "magnitude", "gamma", "central"}
//   next-solar TIME     -> {"peak_utc", "type", "lat_deg", "lon_deg", "magnitude", "gamma"}
//   next-lunar TIME     -> the same, plus "penumbral_magnitude"
// One JSON object per query line. Blank lines and lines starting with '#' are skipped. A bad line
// prints {"error": "line N: ...", "line": N} and the run goes on; the exit status is then 2.
// A bad query given as arguments is reported on stderr with exit status 2.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/cli_parse.hpp"
#include "scene/eclipse_geometry.hpp"
#include "scene/sim_time.hpp"
#include "scene/sky_positions.hpp"
#include "util/cli_main.hpp"

namespace {

constexpr const char* kUsage = "position BODY TIME | eclipse TIME | next-solar TIME | next-lunar TIME";

nlohmann::json event_json(const cupola::EclipseEvent& e, bool lunar) {
    nlohmann::json j = {{"peak_utc", cupola::tt_to_utc_iso(e.peak_tt_s)},
                        {"type", e.type},
                        {"lat_deg", e.lat_deg},
                        {"lon_deg", e.lon_deg},
                        {"magnitude", e.magnitude},
                        {"gamma", e.gamma}};
    if (lunar) j["penumbral_magnitude"] = e.penumbral_magnitude;
    return j;
}

// Answers one query (already split into words); throws std::invalid_argument naming what is wrong.
nlohmann::json answer(const std::vector<std::string>& w) {
    if (w.empty()) throw std::invalid_argument(std::string("empty query; expected ") + kUsage);
    const std::string& cmd = w[0];
    auto need = [&](size_t n, const char* form) {
        if (w.size() != n)
            throw std::invalid_argument("'" + cmd + "' takes " + form + " (got " + std::to_string(w.size() - 1) +
                                        " words)");
    };
    if (cmd == "position") {
        need(3, "BODY TIME");
        const cupola::SkyPosition p = cupola::sky_position(w[1], cupola::utc_iso_to_j2000_seconds(w[2]));
        return {{"ra_deg", p.ra_deg}, {"dec_deg", p.dec_deg}, {"distance_km", p.distance_km}};
    }
    if (cmd == "eclipse") {
        need(2, "TIME");
        const cupola::SolarEclipseAt e = cupola::solar_eclipse_at(cupola::utc_iso_to_j2000_seconds(w[1]));
        return {{"lat_deg", e.lat_deg},     {"lon_deg", e.lon_deg}, {"type", e.type},
                {"magnitude", e.magnitude}, {"gamma", e.gamma},     {"central", e.central}};
    }
    if (cmd == "next-solar" || cmd == "next-lunar") {
        need(2, "TIME");
        const double t = cupola::utc_iso_to_j2000_seconds(w[1]);
        const bool lunar = cmd == "next-lunar";
        return event_json(lunar ? cupola::next_lunar_eclipse(t) : cupola::next_solar_eclipse(t), lunar);
    }
    throw std::invalid_argument("unknown query '" + cmd + "' (expected " + kUsage + ")");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{std::string("cupola-sky: apparent positions and eclipses (ERFA). Queries: ") + kUsage +
                 "; TIME is ISO 8601 UTC. Without a query on the command line, one query per stdin line."};
    std::vector<std::string> query;
    app.add_option("query", query, "one query, e.g. position moon 2024-04-08T18:17:00Z");
    if (const auto stop = cupola::parse_command_line(app, argc, argv, "cupola-sky")) return *stop;
    return cupola::run_main("cupola-sky", [&]() -> int {
        cupola::setup_logging("cupola-sky", false, true);
        if (!query.empty()) {
            std::cout << answer(query).dump() << std::endl;
            return 0;
        }
        int status = 0;
        std::string line;
        for (long n = 1; std::getline(std::cin, line); ++n) {
            const auto first = line.find_first_not_of(" \t\r");
            if (first == std::string::npos || line[first] == '#') continue;
            std::istringstream in(line);
            std::vector<std::string> words;
            for (std::string word; in >> word;) words.push_back(word);
            try {
                std::cout << answer(words).dump() << std::endl;
            } catch (const std::invalid_argument& e) {
                const std::string why = "line " + std::to_string(n) + ": " + e.what();
                std::cout << nlohmann::json{{"error", why}, {"line", n}}.dump() << std::endl;
                status = 2;
            }
        }
        return status;
    });
}

#include "scene/star_catalog.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string_view>

namespace cupola {

glm::dvec3 equatorial_direction(double ra, double dec) {
    return {std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra), std::sin(dec)};
}

glm::dvec3 Star::direction() const { return equatorial_direction(ra_rad, dec_rad); }

namespace {

double parse_number(std::string_view field, const std::string& where, const char* what) {
    while (!field.empty() && field.front() == ' ') field.remove_prefix(1);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\r')) field.remove_suffix(1);
    double v = 0.0;
    auto [p, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (field.empty() || ec != std::errc() || p != field.data() + field.size() || !std::isfinite(v))
        throw std::runtime_error(where + ": " + what + " is not a number: \"" + std::string(field) + "\"");
    return v;
}

}  // namespace

std::vector<Star> load_star_catalog(const std::string& file, double magnitude_limit) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file + ": cannot open star catalogue");
    std::vector<Star> stars;
    std::string line;
    int lineno = 0;
    bool header_seen = false;
    while (std::getline(in, line)) {
        ++lineno;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#') continue;
        const std::string where = file + ":" + std::to_string(lineno);
        if (!header_seen) {
            if (line.rfind("ra_deg,dec_deg,vmag,bv", 0) != 0)
                throw std::runtime_error(where + ": expected the header \"ra_deg,dec_deg,vmag,bv,name\"");
            header_seen = true;
            continue;
        }
        std::vector<std::string_view> f;
        std::string_view rest(line);
        for (;;) {
            auto c = rest.find(',');
            f.push_back(rest.substr(0, c));
            if (c == std::string_view::npos) break;
            rest.remove_prefix(c + 1);
        }
        if (f.size() != 4 && f.size() != 5)
            throw std::runtime_error(where + ": expected 4 or 5 comma-separated columns, found " +
                                     std::to_string(f.size()));
        const double ra = parse_number(f[0], where, "ra_deg");
        const double dec = parse_number(f[1], where, "dec_deg");
        const double v = parse_number(f[2], where, "vmag");
        const double bv = parse_number(f[3], where, "bv");
        if (ra < 0.0 || ra > 360.0) throw std::runtime_error(where + ": ra_deg out of [0,360]");
        if (dec < -90.0 || dec > 90.0) throw std::runtime_error(where + ": dec_deg out of [-90,90]");
        if (v < -30.0 || v > 30.0) throw std::runtime_error(where + ": vmag out of [-30,30]");
        if (bv < -1.0 || bv > 5.0) throw std::runtime_error(where + ": bv out of [-1,5]");
        if (v > magnitude_limit) continue;
        Star s;
        s.ra_rad = ra * std::numbers::pi / 180.0;
        s.dec_rad = dec * std::numbers::pi / 180.0;
        s.v_mag = static_cast<float>(v);
        s.b_minus_v = static_cast<float>(bv);
        if (f.size() == 5) s.name = std::string(f[4]);
        stars.push_back(std::move(s));
    }
    if (!header_seen) throw std::runtime_error(file + ": empty star catalogue (no header line)");
    return stars;
}

}  // namespace cupola

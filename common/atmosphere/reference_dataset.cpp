#include "atmosphere/reference_dataset.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <istream>
#include <iterator>
#include <ostream>
#include <set>
#include <stdexcept>
#include <utility>

namespace cupola::atmosphere {

namespace {

const char* const kRequiredKeys[] = {"preset", "hash", "orders", "paths", "seed", "directions"};

std::string format(const char* fmt, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (;;) {
        const std::size_t end = line.find(sep, start);
        fields.push_back(line.substr(start, end - start));
        if (end == std::string::npos) return fields;
        start = end + 1;
    }
}

class Parser {
public:
    explicit Parser(std::string name) : name_(std::move(name)) {}
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(name_ + ":" + std::to_string(line_) + ": " + what);
    }
    void set_line(int line) { line_ = line; }

    double number(const std::string& field, const char* column) const {
        double v = 0.0;
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
        if (field.empty() || ec != std::errc() || end != field.data() + field.size() || !std::isfinite(v))
            fail(std::string("column ") + column + ": '" + field + "' is not a finite number");
        return v;
    }
    template <class Int>
    Int integer(const std::string& field, const char* what) const {
        Int v = 0;
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
        if (field.empty() || ec != std::errc() || end != field.data() + field.size())
            fail(std::string(what) + ": '" + field + "' is not an integer");
        return v;
    }
    bool flag(const std::string& field, const char* column) const {
        if (field == "0") return false;
        if (field == "1") return true;
        fail(std::string("column ") + column + ": '" + field + "' is not 0 or 1");
    }

private:
    std::string name_;
    int line_ = 0;
};

// "# key=value" with key in [a-z0-9_]+: true and the parts; anything else is a free comment.
bool metadata_line(const std::string& line, std::string& key, std::string& value) {
    if (line.rfind("# ", 0) != 0) return false;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos || eq == 2) return false;
    key = line.substr(2, eq - 2);
    if (!std::all_of(key.begin(), key.end(),
                     [](char ch) { return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_'; }))
        return false;
    value = line.substr(eq + 1);
    return true;
}

// A metadata value as a number (absent: fallback).
double metadata_number(const ReferenceDataset& d, const std::string& key, double fallback) {
    const auto it = d.metadata.find(key);
    if (it == d.metadata.end()) return fallback;
    double v = 0.0;
    const std::string& f = it->second;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v))
        throw std::runtime_error("reference dataset metadata " + key + ": '" + f + "' is not a finite number");
    return v;
}

int metadata_count(const ReferenceDataset& d, const std::string& key, int fallback) {
    const double v = metadata_number(d, key, fallback);
    if (v != std::floor(v) || v < 0.0 || v > 1e9)
        throw std::runtime_error("reference dataset metadata " + key + ": not a count");
    return static_cast<int>(v);
}

bool recomputed_here(const ReferenceDataset& d, double sun_zenith_deg) {
    const auto it = d.metadata.find("recomputed_sun_zenith_deg");
    if (it == d.metadata.end()) return true;
    for (const std::string& f : split(it->second, ',')) {
        double v = 0.0;
        const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
        if (f.empty() || ec != std::errc() || end != f.data() + f.size())
            throw std::runtime_error("reference dataset metadata recomputed_sun_zenith_deg: '" + f +
                                     "' is not a number");
        if (v == sun_zenith_deg) return true;
    }
    return false;
}

}  // namespace

ReferenceSettings row_settings(const ReferenceDataset& d, double sun_zenith_deg) {
    const std::string prefix = recomputed_here(d, sun_zenith_deg) ? "" : "kept_";
    ReferenceSettings s;
    s.scattering_orders = prefix.empty() ? d.orders : metadata_count(d, "kept_orders", d.orders);
    s.ms_paths = prefix.empty() ? d.paths : metadata_count(d, "kept_paths", d.paths);
    s.seed = prefix.empty() ? d.seed : static_cast<std::uint64_t>(metadata_count(d, "kept_seed", 1));
    const auto est = d.metadata.find(prefix + "ms_estimator");
    const std::string estimator = est == d.metadata.end() ? "collision" : est->second;
    if (estimator != "collision" && estimator != "lit_segment")
        throw std::runtime_error("reference dataset metadata " + prefix + "ms_estimator: '" + estimator +
                                 "' is neither collision nor lit_segment");
    s.ms_estimator = estimator == "collision" ? MsEstimator::kCollision : MsEstimator::kLitSegment;
    s.ms_max_paths = metadata_count(d, prefix + "ms_max_paths", 0);
    s.ms_target_noise = metadata_number(d, prefix + "ms_target_noise", 0.0);
    s.ms_target_floor = metadata_number(d, prefix + "ms_target_floor", 0.0);
    return s;
}

ReferenceRow make_reference_row(const ValidationCase& c, const SkyRadiance& s) {
    ReferenceRow row;
    row.c = c;
    row.hits_ground = s.hits_ground;
    row.in_atmosphere = s.in_atmosphere;
    row.luminance = s.luminance;
    row.luminance_stderr = s.multiple_luminance_stderr;
    row.rgb = s.rgb;
    row.xyz = s.xyz;
    return row;
}

void write_reference_dataset(std::ostream& out, const ReferenceDataset& d, const std::vector<std::string>& comments) {
    for (const std::string& c : comments) out << "# " << c << "\n";
    out << "# preset=" << d.preset << "\n# hash=" << d.hash << "\n# orders=" << d.orders << "\n# paths=" << d.paths
        << "\n# seed=" << d.seed << "\n# directions=" << d.directions << "\n";
    for (const auto& [key, value] : d.metadata)
        if (std::find(std::begin(kRequiredKeys), std::end(kRequiredKeys), key) == std::end(kRequiredKeys))
            out << "# " << key << "=" << value << "\n";
    out << kReferenceCsvHeader << "\n";
    for (const ReferenceRow& r : d.rows) {
        const SkyQuery& q = r.c.query;
        out << r.c.camera;
        for (double v : {q.altitude_m, q.view_zenith_deg, q.sun_zenith_deg, q.relative_azimuth_deg})
            out << "," << format("%.17g", v);
        out << "," << (r.hits_ground ? 1 : 0) << "," << (r.in_atmosphere ? 1 : 0);
        for (double v : {r.luminance, r.luminance_stderr, r.rgb.r, r.rgb.g, r.rgb.b, r.xyz.x, r.xyz.y, r.xyz.z})
            out << "," << format("%.9g", v);
        out << "\n";
    }
}

ReferenceDataset read_reference_dataset(std::istream& in, const std::string& name) {
    static const char* const kColumns[] = {"camera",
                                           "altitude_m",
                                           "view_zenith_deg",
                                           "sun_zenith_deg",
                                           "relative_azimuth_deg",
                                           "hits_ground",
                                           "in_atmosphere",
                                           "luminance",
                                           "luminance_stderr",
                                           "r",
                                           "g",
                                           "b",
                                           "x",
                                           "y",
                                           "z"};
    constexpr std::size_t kFields = std::size(kColumns);
    const std::set<std::string> cameras(validation_cameras().begin(), validation_cameras().end());

    ReferenceDataset d;
    Parser p(name);
    bool header_seen = false;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        p.set_line(number);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        if (!header_seen) {
            if (line[0] == '#') {
                std::string key, value;
                if (metadata_line(line, key, value) && !d.metadata.emplace(key, value).second)
                    p.fail("metadata '" + key + "' given twice");
                continue;
            }
            if (line != kReferenceCsvHeader) p.fail(std::string("expected the header '") + kReferenceCsvHeader + "'");
            for (const char* key : kRequiredKeys)
                if (!d.metadata.count(key)) p.fail(std::string("metadata '# ") + key + "=' missing before the header");
            d.preset = d.metadata["preset"];
            d.hash = d.metadata["hash"];
            d.orders = p.integer<int>(d.metadata["orders"], "metadata orders");
            d.paths = p.integer<int>(d.metadata["paths"], "metadata paths");
            d.seed = p.integer<std::uint64_t>(d.metadata["seed"], "metadata seed");
            d.directions = p.integer<int>(d.metadata["directions"], "metadata directions");
            header_seen = true;
            continue;
        }
        const std::vector<std::string> f = split(line, ',');
        if (f.size() != kFields)
            p.fail("expected " + std::to_string(kFields) + " fields, found " + std::to_string(f.size()));
        ReferenceRow r;
        if (!cameras.count(f[0])) p.fail("unknown camera '" + f[0] + "'");
        r.c.camera = f[0];
        r.c.query.altitude_m = p.number(f[1], kColumns[1]);
        r.c.query.view_zenith_deg = p.number(f[2], kColumns[2]);
        r.c.query.sun_zenith_deg = p.number(f[3], kColumns[3]);
        r.c.query.relative_azimuth_deg = p.number(f[4], kColumns[4]);
        r.hits_ground = p.flag(f[5], kColumns[5]);
        r.in_atmosphere = p.flag(f[6], kColumns[6]);
        r.luminance = p.number(f[7], kColumns[7]);
        r.luminance_stderr = p.number(f[8], kColumns[8]);
        for (int k = 0; k < 3; ++k) {
            r.rgb[k] = p.number(f[9 + k], kColumns[9 + k]);
            r.xyz[k] = p.number(f[12 + k], kColumns[12 + k]);
        }
        d.rows.push_back(std::move(r));
    }
    if (in.bad()) throw std::runtime_error(name + ": read error");
    if (!header_seen)
        throw std::runtime_error(name + ": no header line '" + kReferenceCsvHeader + "' (empty or comments only)");
    return d;
}

ReferenceDataset read_reference_dataset(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    return read_reference_dataset(in, path);
}

}  // namespace cupola::atmosphere

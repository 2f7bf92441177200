#include "atmosphere/production_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

namespace cupola::atmosphere {

glm::dvec2 chromaticity_uv(const glm::dvec3& c) {
    const double den = c.x + 15.0 * c.y + 3.0 * c.z;
    if (!(den > 0.0)) return glm::dvec2(0.0);
    return glm::dvec2(4.0 * c.x / den, 9.0 * c.y / den);
}

bool reference_is_limited(const ReferenceRow& row) {
    return !(row.luminance > 0.0) || row.luminance_stderr > kMaxReferenceNoise * row.luminance;
}

namespace {
struct Samples {
    std::vector<double> rel, signed_rel, chroma, noise;
    int skipped = 0, nonzero = 0, below_floor = 0, limited = 0;
};

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto i = static_cast<std::size_t>(pos);
    const double f = pos - static_cast<double>(i);
    return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

ErrorStats summarise(const std::string& camera, double sun, const Samples& s) {
    ErrorStats e;
    e.camera = camera;
    e.sun_zenith_deg = sun;
    e.used = static_cast<int>(s.rel.size());
    e.skipped = s.skipped;
    e.nonzero_where_reference_is_zero = s.nonzero;
    e.below_floor = s.below_floor;
    e.reference_limited = s.limited;
    e.median = percentile(s.rel, 0.5);
    e.p99 = percentile(s.rel, 0.99);
    e.max = s.rel.empty() ? 0.0 : *std::max_element(s.rel.begin(), s.rel.end());
    double sum = 0.0;
    for (double x : s.signed_rel) sum += x;
    e.mean_signed = s.signed_rel.empty() ? 0.0 : sum / static_cast<double>(s.signed_rel.size());
    e.chroma_median = percentile(s.chroma, 0.5);
    e.chroma_p99 = percentile(s.chroma, 0.99);
    e.reference_noise_median = percentile(s.noise, 0.5);
    return e;
}

void append(Samples& to, const Samples& from) {
    to.rel.insert(to.rel.end(), from.rel.begin(), from.rel.end());
    to.signed_rel.insert(to.signed_rel.end(), from.signed_rel.begin(), from.signed_rel.end());
    to.chroma.insert(to.chroma.end(), from.chroma.begin(), from.chroma.end());
    to.noise.insert(to.noise.end(), from.noise.begin(), from.noise.end());
    to.skipped += from.skipped;
    to.nonzero += from.nonzero;
    to.below_floor += from.below_floor;
    to.limited += from.limited;
}
}  // namespace

AccuracyReport measure_accuracy(const ProductionAtmosphere& model, const ReferenceDataset& reference) {
    std::vector<std::pair<std::string, double>> order;
    std::map<std::pair<std::string, double>, Samples> groups;
    const auto start = std::chrono::steady_clock::now();
    for (const ReferenceRow& row : reference.rows) {
        const auto key = std::make_pair(row.c.camera, row.c.query.sun_zenith_deg);
        if (!groups.count(key)) order.push_back(key);
        Samples& s = groups[key];
        const ProductionRadiance p = model.sky(row.c.query);
        if (!row.in_atmosphere) {  // the ray misses the atmosphere: both must be exactly 0
            ++s.skipped;
            if (p.luminance != 0.0) ++s.nonzero;
            continue;
        }
        // No Monte Carlo path reached sunlight (night side): the reference is 0 +- unknown.
        if (reference_is_limited(row)) {
            ++s.limited;
            continue;
        }
        if (row.luminance < kLuminanceFloor) ++s.below_floor;
        const double d = (p.luminance - row.luminance) / std::max(row.luminance, kLuminanceFloor);
        s.rel.push_back(std::fabs(d));
        s.signed_rel.push_back(d);
        s.chroma.push_back(glm::length(chromaticity_uv(p.xyz) - chromaticity_uv(row.xyz)));
        s.noise.push_back(row.luminance_stderr / row.luminance);
    }
    AccuracyReport r;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.seconds_per_query = reference.rows.empty() ? 0.0 : seconds / static_cast<double>(reference.rows.size());
    Samples all;
    for (const auto& key : order) {
        r.groups.push_back(summarise(key.first, key.second, groups[key]));
        append(all, groups[key]);
    }
    r.overall = summarise("all", -1.0, all);
    return r;
}

}  // namespace cupola::atmosphere

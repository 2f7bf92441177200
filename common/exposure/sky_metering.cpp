#include "exposure/sky_metering.hpp"

#include <algorithm>
#include <cmath>

namespace cupola {

namespace {

bool lit_value(double l) { return std::isfinite(l) && l > 0.0; }

// The weighted quantile q of the samples (sorted by luminance): the lowest luminance at which the
// weight of the samples at or below it reaches q of the total.
double weighted_quantile(std::vector<MeterSample> lit, double q) {
    if (lit.empty()) return 0.0;
    std::sort(lit.begin(), lit.end(),
              [](const MeterSample& a, const MeterSample& b) { return a.luminance < b.luminance; });
    double total = 0.0;
    for (const MeterSample& s : lit) total += s.weight;
    double below = 0.0;
    for (const MeterSample& s : lit) {
        below += s.weight;
        if (below >= q * total) return s.luminance;
    }
    return lit.back().luminance;
}

// The samples of weight > 0 whose luminance is at least `floor` and finite and positive.
std::vector<MeterSample> samples_above(const std::vector<MeterSample>& samples, double floor) {
    std::vector<MeterSample> out;
    for (const MeterSample& s : samples)
        if (s.weight > 0.0 && lit_value(s.luminance) && s.luminance >= floor) out.push_back(s);
    return out;
}

}  // namespace

SkyMetering meter_sky(const std::vector<MeterSample>& samples) {
    SkyMetering m;
    double brightest = 0.0, all_weight = 0.0;
    for (const MeterSample& s : samples) {
        if (!(s.weight > 0.0)) continue;
        all_weight += s.weight;
        if (lit_value(s.luminance)) brightest = std::max(brightest, s.luminance);
    }
    if (!(brightest > 0.0)) return m;
    m.highlight = weighted_quantile(samples_above(samples, SkyMetering::kSeenContrast * brightest),
                                    SkyMetering::kHighlightQuantile);
    double log_sum = 0.0, lit_weight = 0.0;
    for (const MeterSample& s : samples_above(samples, SkyMetering::kLitContrast * m.highlight)) {
        log_sum += s.weight * std::log(s.luminance);
        lit_weight += s.weight;
    }
    m.log_average = std::exp(log_sum / lit_weight);
    m.lit_fraction = lit_weight / all_weight;
    return m;
}

double image_plane_cell_solid_angle(double x, double y, double dx, double dy) {
    const double r2 = 1.0 + x * x + y * y;
    return dx * dy / (r2 * std::sqrt(r2));
}

}  // namespace cupola

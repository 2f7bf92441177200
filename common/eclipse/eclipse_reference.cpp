#include "eclipse/eclipse_reference.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <numbers>
#include <queue>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "image/table_file.hpp"
#include "shading/shader_sources.hpp"
#include "shading/shared_shading.hpp"

namespace cupola::eclipse {

namespace {

// 21-point Gauss-Kronrod rule on [-1, 1] (QUADPACK qk21): Kronrod nodes/weights, x >= 0 half;
// the odd entries 1, 3, 5, 7, 9 are the 10-point Gauss nodes, with Gauss weights kG10.
constexpr double kXK[11] = {0.995657163025808080735527280689003,
                            0.973906528517171720077964012084452,
                            0.930157491355708226001207180059508,
                            0.865063366688984510732096688423493,
                            0.780817726586416897063717578345042,
                            0.679409568299024406234327365114874,
                            0.562757134668604683339000099272694,
                            0.433395394129247190799265943165784,
                            0.294392862701460198131126603103866,
                            0.148874338981631210884826001129720,
                            0.0};
constexpr double kWK[11] = {
    0.011694638867371874278064396062192, 0.032558162307964727478818972459390, 0.054755896574351996031381300244580,
    0.075039674810919952767043140916190, 0.093125454583697605535065465083366, 0.109387158802297641899210590325805,
    0.123491976262065851077208980297514, 0.134709217311473325928054001771707, 0.142775938577060080797094273138717,
    0.147739104901338491374841515972068, 0.149445554002916905664936468389821};
constexpr double kG10[5] = {0.066671344308688137593568809893332, 0.149451349150580593145776339657697,
                            0.219086362515982043995534934228163, 0.269266719309996355091226921569469,
                            0.295524224714752870173892994651338};

// Absolute tolerance on the occluded flux (total flux >= 2 pi / 3): the reference proper, and the
// table's (stored as float, so 1e-10 is already 1000x below its rounding).
constexpr double kTolerance = 1e-14;
constexpr double kTableTolerance = 1e-10;

struct Interval {
    double lo, hi, value, error;
    bool operator<(const Interval& o) const { return error < o.error; }  // max-heap on error
};

template <class F>
Interval gauss_kronrod21(const F& f, double lo, double hi, int64_t& evaluations) {
    const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    const double fc = f(c);
    double k = kWK[10] * fc, g = 0.0;
    for (int i = 0; i < 10; ++i) {
        const double dx = h * kXK[i];
        const double f2 = f(c - dx) + f(c + dx);
        k += kWK[i] * f2;
        if (i % 2 == 1) g += kG10[i / 2] * f2;
    }
    evaluations += 21;
    return {lo, hi, k * h, std::fabs((k - g) * h)};
}

// Globally adaptive integration of f over the given pieces (breakpoints between them), to an
// absolute error bound tol or at most max_intervals intervals.
template <class F>
double integrate(const F& f, const std::vector<std::pair<double, double>>& pieces, double tol, double& error,
                 int64_t& evaluations) {
    std::priority_queue<Interval> heap;
    double err = 0.0;
    for (const auto& [lo, hi] : pieces)
        if (hi > lo) {
            const Interval i = gauss_kronrod21(f, lo, hi, evaluations);
            err += i.error;
            heap.push(i);
        }
    const auto total_error = [&] {
        double e = 0.0;
        auto copy = heap;
        while (!copy.empty()) e += copy.top().error, copy.pop();
        return e;
    };
    const int max_intervals = 4000;  // ~20 ms; never reached in tests (rounding-noise guard)
    while (err > tol && !heap.empty() && static_cast<int>(heap.size()) < max_intervals) {
        const Interval worst = heap.top();
        const double mid = 0.5 * (worst.lo + worst.hi);
        if (!(mid > worst.lo && mid < worst.hi)) break;  // cannot split further in double
        heap.pop();
        const Interval left = gauss_kronrod21(f, worst.lo, mid, evaluations);
        const Interval right = gauss_kronrod21(f, mid, worst.hi, evaluations);
        err += left.error + right.error - worst.error;
        heap.push(left);
        heap.push(right);
        if (heap.size() % 256 == 0) err = total_error();  // drop accumulated rounding of the running sum
    }
    // Sum the smallest contributions first.
    std::vector<double> values;
    error = 0.0;
    while (!heap.empty()) {
        values.push_back(heap.top().value);
        error += heap.top().error;
        heap.pop();
    }
    std::sort(values.begin(), values.end(), [](double x, double y) { return std::fabs(x) < std::fabs(y); });
    double sum = 0.0;
    for (double v : values) sum += v;
    return sum;
}

ReferenceResult reference(double a, double s, double u, double tol) {
    if (!(a > 0.0) || !std::isfinite(a) || !std::isfinite(s) || !(u >= 0.0 && u <= 1.0))
        throw std::invalid_argument("eclipse reference: need a > 0 finite, s finite, u in [0, 1] (a=" +
                                    std::to_string(a) + ", s=" + std::to_string(s) + ", u=" + std::to_string(u) + ")");
    s = std::fabs(s);
    ReferenceResult r;
    r.error_bound = 0.0;
    if (s >= 1.0 + a) return r;  // no overlap (first contact or beyond)
    if (a >= 1.0 + s) {          // the Sun lies inside the occluder
        r.visible = 0.0;
        return r;
    }
    constexpr double pi = std::numbers::pi;
    const double total = pi * (1.0 - u / 3.0);
    // Radical line x0 (where the Sun's and the occluder's chords are equal): the chord is the
    // occluder's for x < x0 and the Sun's for x > x0. Written to avoid cancellation: near a = 1
    // through (1 - a)(1 + a), for large a through (s - a)(s + a) (|s - a| <= 1 here).
    double x0 = 0.0;
    if (s > 0.0)
        x0 = (a < 2.0 ? (1.0 - a) * (1.0 + a) + s * s : 1.0 + (s - a) * (s + a)) / (2.0 * s);
    else
        x0 = a < 1.0 ? HUGE_VAL : -HUGE_VAL;  // concentric: the smaller disc's chord everywhere
    const double xl = std::max(-1.0, s - a), xr = std::min(1.0, s + a);
    const double one_minus_a2 = (1.0 - a) * (1.0 + a);

    // Flux of the chord |y| <= Y at abscissa x, with D = h^2 - Y^2 >= 0 given separately.
    const auto chord_flux = [u](double Y, double h2, double D) {
        const double sd = std::sqrt(std::max(D, 0.0));
        return 2.0 * Y * (1.0 - u) + u * (Y * sd + h2 * std::atan2(Y, sd));
    };
    // Occluder side: Y^2 = a^2 - (x - s)^2 = ((a + s) - x)(x - (s - a)), s - a formed first
    // (a + x - s would lose x against a huge a); D = 2 s (x0 - x).
    const double s_minus_a = s - a, s_plus_a = s + a;
    const auto occluder_side = [&](double x) {
        const double Y = std::sqrt(std::max((s_plus_a - x) * (x - s_minus_a), 0.0));
        const double h2 = (1.0 - x) * (1.0 + x);
        const double D = s > 0.0 ? 2.0 * s * (x0 - x) : one_minus_a2;
        return chord_flux(Y, h2, D);
    };
    // Sun side: Y = h, D = 0: 2 h (1 - u) + u h^2 pi / 2.
    const auto sun_side = [&](double x) {
        const double h2 = std::max((1.0 - x) * (1.0 + x), 0.0);
        return 2.0 * std::sqrt(h2) * (1.0 - u) + u * h2 * (0.5 * pi);
    };
    double e1 = 0.0, e2 = 0.0;
    const double occ_l = integrate(occluder_side, {{xl, std::min(x0, xr)}}, 0.5 * tol, e1, r.evaluations);
    const double occ_r = integrate(sun_side, {{std::max(x0, xl), xr}}, 0.5 * tol, e2, r.evaluations);
    const double occluded = occ_l + occ_r;
    r.visible = std::clamp(1.0 - occluded / total, 0.0, 1.0);
    r.error_bound = (e1 + e2) / total;
    return r;
}

}  // namespace

ReferenceResult visible_fraction_reference_detail(double a, double s, double u) {
    return reference(a, s, u, kTolerance);
}

double visible_fraction_reference(double a, double s, double u) { return reference(a, s, u, kTolerance).visible; }

namespace {

shading::Texture2DData compute_lut(double u, int width, int height) {
    shading::Texture2DData t;
    t.width = width;
    t.height = height;
    t.texels.assign(static_cast<size_t>(width) * height, glm::vec4(0.0f));
    std::atomic<int> next_row{0};
    const auto work = [&] {
        for (int j; (j = next_row.fetch_add(1)) < height;)
            for (int i = 0; i < width; ++i) {
                // The shader's own inverse mapping (float), so texel and lookup agree exactly.
                const glm::vec2 as =
                    shading::eclipse_lut_parameters(glm::vec2(static_cast<float>(i) / static_cast<float>(width - 1),
                                                              static_cast<float>(j) / static_cast<float>(height - 1)));
                const float v = static_cast<float>(reference(as.x, as.y, u, kTableTolerance).visible);
                t.texels[static_cast<size_t>(j) * width + i] = glm::vec4(v, v, v, 1.0f);
            }
    };
    const unsigned n = std::max(1u, std::min(std::thread::hardware_concurrency(), static_cast<unsigned>(height)));
    std::vector<std::thread> threads;
    for (unsigned k = 1; k < n; ++k) threads.emplace_back(work);
    work();
    for (auto& th : threads) th.join();
    return t;
}

}  // namespace

namespace {

void check_lut_request(double u, int width, int height) {
    if (width < 2 || height < 2)
        throw std::invalid_argument("eclipse LUT: need width, height >= 2 (got " + std::to_string(width) + " x " +
                                    std::to_string(height) + ")");
    if (!(u >= 0.0 && u <= 1.0))
        throw std::invalid_argument("eclipse LUT: need u in [0, 1] (got " + std::to_string(u) + ")");
}

}  // namespace

// The cache key holds the table's inputs and the texts of the code that computes it: this file
// (hashed by the build) and the shared shading (the texel-to-parameter mapping).
shading::Texture2DData load_or_compute_eclipse_lut(double u, int width, int height) {
    check_lut_request(u, width, height);
    static constexpr const char* kFormat = "cupola-eclipse-table-v1";
    std::string text = fmt::format("{}|{:a}|{}x{}|{:a}|{}", kFormat, u, width, height, kTableTolerance,
                                   CUPOLA_ECLIPSE_REFERENCE_SHA256);
    for (const char* f : kSharedShadingFiles) text += shader_source(f);
    const std::filesystem::path dir = cache_directory("eclipse");
    const std::filesystem::path file = dir / ("eclipse-table-" + cache_key_hex(text) + ".exr");
    shading::Texture2DData t;
    std::string why;
    if (std::filesystem::exists(file)) {
        if (read_table_file(file, width, height, kFormat, t, why)) return t;
        spdlog::warn("eclipse table: cached {} is unusable ({}); rebuilding", file.string(), why);
    }
    t = compute_lut(u, width, height);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !write_table_file(file, t, kFormat))
        spdlog::warn("eclipse table: could not write the cache in {}", dir.string());
    return t;
}

shading::Texture2DData build_eclipse_lut(double u, int width, int height) {
    check_lut_request(u, width, height);
    // Every renderer of a process asks for the same table: computed (or read) once per (u, size).
    static std::mutex mutex;
    static std::map<std::tuple<double, int, int>, shading::Texture2DData> cache;
    const std::lock_guard<std::mutex> lock(mutex);
    const auto key = std::make_tuple(u, width, height);
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, load_or_compute_eclipse_lut(u, width, height)).first;
    return it->second;
}

shading::Texture2DData compute_eclipse_lut(double u, int width, int height) {
    check_lut_request(u, width, height);
    return compute_lut(u, width, height);
}

}  // namespace cupola::eclipse

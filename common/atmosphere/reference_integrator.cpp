#include "atmosphere/reference_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "atmosphere/atmosphere_geometry.hpp"

namespace cupola::atmosphere {
namespace {

constexpr double kPi = std::numbers::pi;

// 5-point Gauss-Legendre on [-1, 1].
constexpr double kGlX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
constexpr double kGlW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                            0.2369268850561891};

// xoshiro256** (Blackman & Vigna 2018), seeded through splitmix64.
class Rng {
public:
    Rng(std::uint64_t seed, std::uint64_t stream) {
        std::uint64_t x = seed * 0x9E3779B97F4A7C15ull ^ (stream + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull;
        for (auto& s : s_) s = splitmix(x);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

private:
    static std::uint64_t splitmix(std::uint64_t& x) {
        std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t next() {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }
    std::uint64_t s_[4];
};

// An orthonormal frame around unit w; returns w rotated so that its polar angle is acos(cos_t).
glm::dvec3 direction_around(const glm::dvec3& w, double cos_t, double phi) {
    const glm::dvec3 a = std::abs(w.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(a, w));
    const glm::dvec3 v = glm::cross(w, u);
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    return glm::normalize(sin_t * std::cos(phi) * u + sin_t * std::sin(phi) * v + cos_t * w);
}

// Inverse CDF of the Rayleigh phase function in nu: nu^3 + 3 nu = 8 u - 4 (Cardano, one real root).
double sample_rayleigh_nu(double u) {
    const double q = 8.0 * u - 4.0;
    const double s = std::sqrt(0.25 * q * q + 1.0);
    return std::clamp(std::cbrt(0.5 * q + s) + std::cbrt(0.5 * q - s), -1.0, 1.0);
}

double sample_hg_nu(double g, double u) {
    if (std::abs(g) < 1e-4) return 2.0 * u - 1.0;
    const double f = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return std::clamp((1.0 + g * g - f * f) / (2.0 * g), -1.0, 1.0);
}

}  // namespace

double rayleigh_phase(double nu) { return 3.0 / (16.0 * kPi) * (1.0 + nu * nu); }

double cornette_shanks_phase(double g, double nu) {
    const double g2 = g * g;
    const double denom = std::max(1.0 + g2 - 2.0 * g * nu, 1e-300);
    return 3.0 / (8.0 * kPi) * (1.0 - g2) * (1.0 + nu * nu) / ((2.0 + g2) * denom * std::sqrt(denom));
}

double henyey_greenstein_phase(double g, double nu) {
    const double g2 = g * g;
    const double denom = std::max(1.0 + g2 - 2.0 * g * nu, 1e-300);
    return (1.0 - g2) / (4.0 * kPi * denom * std::sqrt(denom));
}

std::vector<double> default_wavelengths() {
    std::vector<double> w;
    for (int l = 360; l <= 830; l += 10) w.push_back(l);
    return w;
}

struct ReferenceIntegrator::Segment {
    glm::dvec3 o{0.0}, v{0.0};
    double length = 0.0;
    std::vector<double> t;        // panel boundaries, t.front() = 0, t.back() = length
    std::vector<glm::dvec3> cum;  // column densities from 0 to t[i]
};

ReferenceIntegrator::ReferenceIntegrator(AtmosphereParameters params, ReferenceSettings settings)
    : params_(std::move(params)), settings_(std::move(settings)), color_(settings_.wavelengths_nm) {
    if (!(params_.top_radius > params_.bottom_radius) || !(params_.bottom_radius > 0.0))
        throw std::invalid_argument("AtmosphereParameters: need 0 < bottom_radius < top_radius");
    if (settings_.scattering_orders < 1) throw std::invalid_argument("ReferenceSettings: scattering_orders >= 1");
    if (!(settings_.panel_height_m > 0.0) || !(settings_.ms_panel_height_m > 0.0))
        throw std::invalid_argument("ReferenceSettings: panel heights must be > 0");
    if (settings_.ms_first_order < 1 || settings_.ms_first_order > 2)
        throw std::invalid_argument("ReferenceSettings: ms_first_order is 1 or 2");
    for (double l : settings_.wavelengths_nm) {
        beta_r_.push_back(params_.rayleigh_scattering(l));
        beta_ms_.push_back(params_.mie_scattering(l));
        beta_me_.push_back(params_.mie_extinction(l));
        beta_o_.push_back(params_.ozone_absorption(l));
        sun_.push_back(params_.solar_irradiance(l));
        albedo_.push_back(params_.ground_albedo(l));
    }
    if (!(settings_.ms_target_noise >= 0.0))
        throw std::invalid_argument("ReferenceSettings: ms_target_noise must be >= 0");
    for (std::size_t k = 0; k < settings_.wavelengths_nm.size(); ++k)
        if (std::abs(settings_.wavelengths_nm[k] - 550.0) < std::abs(settings_.wavelengths_nm[proxy_k_] - 550.0))
            proxy_k_ = k;
    if (settings_.ms_estimator == MsEstimator::kLitSegment && settings_.ms_paths > 0 &&
        settings_.scattering_orders >= settings_.ms_first_order)
        build_sun_proxy();
}

namespace {
// The proxy table's size and its parameterisation of (r, mu_s) for rays that miss the ground:
// x_r = rho / H and x_mu = (d - d_min) / (d_max - d_min), with rho the distance to the horizon,
// H its value at the top, d the distance to the top boundary along the ray (Bruneton 2017,
// the transmittance table's mapping in its "Precomputations" part): the grazing rays, where the
// transmittance changes fastest, get the most entries.
constexpr int kProxyR = 32, kProxyMu = 128;
// The twilight lobe: at a vertex in the planet's shadow, this share of the new directions is drawn
// from a Henyey-Greenstein lobe (this g) around the direction toward the nearest point of the
// terminator circle (the sunlit side of the shadow's edge, at this altitude), where the bright
// twilight air is; the rest from the phase function (or cosine). Both are in the density, so the
// weights stay bounded by 1 / (1 - share) times the unmixed ones (Veach 1997, section 9.2).
constexpr double kTwilightLobeShare = 0.5, kTwilightLobeG = 0.75, kTwilightAltitude_m = 30000.0;
struct ProxyCoord {
    double r, mu;
};
ProxyCoord proxy_coord_inverse(double x_r, double x_mu, double R, double top) {
    const double H = std::sqrt(top * top - R * R), rho = H * x_r;
    const double r = std::sqrt(rho * rho + R * R);
    const double d_min = top - r, d_max = rho + H, d = d_min + x_mu * (d_max - d_min);
    const double mu = d <= 0.0 ? 1.0 : std::clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
    return {r, mu};
}
}  // namespace

void ReferenceIntegrator::build_sun_proxy() {
    const double R = params_.bottom_radius, top = params_.top_radius;
    const double e_lum = color_.luminance(sun_);
    std::vector<double> ts, lit(sun_.size());
    sun_proxy_log_.assign(static_cast<std::size_t>(kProxyR) * kProxyMu, 0.0);
    for (int i = 0; i < kProxyR; ++i)
        for (int j = 0; j < kProxyMu; ++j) {
            // Just inside the last column, whose ray is exactly tangent to the ground.
            const double x_mu = std::min(j / (kProxyMu - 1.0), 1.0 - 1e-9);
            const ProxyCoord c = proxy_coord_inverse(i / (kProxyR - 1.0), x_mu, R, top);
            const glm::dvec3 sun(std::sqrt(std::max(0.0, 1.0 - c.mu * c.mu)), 0.0, c.mu);
            sun_transmittance(glm::dvec3(0.0, 0.0, c.r), sun, settings_.ms_panel_height_m, ts);
            for (std::size_t k = 0; k < ts.size(); ++k) lit[k] = ts[k] * sun_[k];
            const double t = e_lum > 0.0 ? color_.luminance(lit) / e_lum : 0.0;
            sun_proxy_log_[static_cast<std::size_t>(i) * kProxyMu + j] = std::log(std::max(t, 1e-200));
        }
}

double ReferenceIntegrator::sun_proxy(const glm::dvec3& p, const glm::dvec3& sun) const {
    const double R = params_.bottom_radius, top = params_.top_radius;
    const double len = glm::length(p);
    const double r = std::clamp(len, R, top);
    const double mu = std::clamp(glm::dot(p, sun) / std::max(len, 1e-300), -1.0, 1.0);
    if (f64::ray_hits_sphere(r, mu, R)) return 0.0;
    const double H = std::sqrt(top * top - R * R), rho = std::sqrt(std::max(r * r - R * R, 0.0));
    const double d = f64::ray_sphere_far_m(r, mu, top), d_min = top - r, d_max = rho + H;
    const double x_mu = d_max > d_min ? std::clamp((d - d_min) / (d_max - d_min), 0.0, 1.0) : 0.0;
    const double fr = std::clamp(rho / H, 0.0, 1.0) * (kProxyR - 1), fm = x_mu * (kProxyMu - 1);
    const int i = std::min(static_cast<int>(fr), kProxyR - 2), j = std::min(static_cast<int>(fm), kProxyMu - 2);
    const double a = fr - i, b = fm - j;
    auto at = [&](int ii, int jj) { return sun_proxy_log_[static_cast<std::size_t>(ii) * kProxyMu + jj]; };
    const double v =
        (1 - a) * ((1 - b) * at(i, j) + b * at(i, j + 1)) + a * ((1 - b) * at(i + 1, j) + b * at(i + 1, j + 1));
    return std::max(std::exp(v), 1e-200);
}

glm::dvec3 ReferenceIntegrator::densities(const glm::dvec3& p) const {
    const double r = glm::length(p);
    if (r > params_.top_radius) return glm::dvec3(0.0);
    const double h = r - params_.bottom_radius;
    return {params_.rayleigh_density(h), params_.mie_density(h), params_.ozone_density(h)};
}

ReferenceIntegrator::Segment ReferenceIntegrator::make_segment(const glm::dvec3& origin, const glm::dvec3& dir,
                                                               double length, double panel_h,
                                                               const std::vector<double>& extra_splits) const {
    Segment s;
    s.o = origin;
    s.v = dir;
    s.length = std::max(length, 0.0);
    std::vector<double> splits = {0.0, s.length};
    const double b = glm::dot(origin, dir);
    const double c = glm::dot(origin, origin);
    splits.push_back(-b);  // closest approach to the centre
    for (double h :
         {params_.ozone_bottom, params_.ozone_peak, params_.ozone_top, params_.top_radius - params_.bottom_radius}) {
        const double rk = params_.bottom_radius + h;
        const double disc = b * b - c + rk * rk;
        if (disc < 0.0) continue;
        const double sq = std::sqrt(disc);
        splits.push_back(-b - sq);
        splits.push_back(-b + sq);
    }
    splits.insert(splits.end(), extra_splits.begin(), extra_splits.end());
    std::erase_if(splits, [&](double t) { return !(t >= 0.0 && t <= s.length); });
    std::sort(splits.begin(), splits.end());
    const double merge = 1e-9 * std::max(1.0, s.length);
    s.t.push_back(0.0);
    for (std::size_t k = 1; k < splits.size(); ++k) {
        const double end = splits[k];
        double t = s.t.back();
        if (end - t <= merge) continue;
        while (end - t > merge) {
            const glm::dvec3 p = origin + t * dir;
            const double r = glm::length(p);
            const double h = std::max(r - params_.bottom_radius, 0.0);
            const double mu = r > 0.0 ? glm::dot(p, dir) / r : 1.0;
            const double dh = panel_h * (1.0 + h / 10000.0);
            double dt = std::min(dh / std::max(std::abs(mu), 1e-12), std::sqrt(2.0 * r * dh));
            dt = std::max(dt, 1e-3 * panel_h);
            double next = t + dt;
            if (next > end - 0.2 * dt) next = end;  // no sliver panel at the end of a piece
            s.t.push_back(next);
            t = next;
        }
    }
    if (s.t.size() == 1) s.t.push_back(s.length);  // zero-length segment: one empty panel
    s.cum.assign(s.t.size(), glm::dvec3(0.0));
    for (std::size_t i = 1; i < s.t.size(); ++i) {
        const double a = s.t[i - 1], half = 0.5 * (s.t[i] - a), mid = a + half;
        glm::dvec3 sum(0.0);
        for (int k = 0; k < 5; ++k) sum += kGlW[k] * densities(origin + (mid + half * kGlX[k]) * dir);
        s.cum[i] = s.cum[i - 1] + half * sum;
    }
    return s;
}

glm::dvec3 ReferenceIntegrator::segment_column(const Segment& s, double t) const {
    t = std::clamp(t, 0.0, s.length);
    std::size_t i = static_cast<std::size_t>(std::upper_bound(s.t.begin(), s.t.end(), t) - s.t.begin());
    i = std::clamp<std::size_t>(i, 1, s.t.size() - 1) - 1;  // panel [t[i], t[i+1]]
    const double a = s.t[i];
    if (t <= a) return s.cum[i];
    const double half = 0.5 * (t - a), mid = a + half;
    glm::dvec3 sum(0.0);
    for (int k = 0; k < 5; ++k) sum += kGlW[k] * densities(s.o + (mid + half * kGlX[k]) * s.v);
    return s.cum[i] + half * sum;
}

double ReferenceIntegrator::sample_segment(const Segment& s, const glm::dvec3& sigma, double tau) const {
    // Panel containing the target optical depth, then safeguarded Newton within it.
    std::size_t i = 1;
    while (i + 1 < s.t.size() && glm::dot(sigma, s.cum[i]) < tau) ++i;
    double lo = s.t[i - 1], hi = s.t[i];
    const double tau_lo = glm::dot(sigma, s.cum[i - 1]), tau_hi = glm::dot(sigma, s.cum[i]);
    double t =
        tau_hi > tau_lo ? lo + (hi - lo) * std::clamp((tau - tau_lo) / (tau_hi - tau_lo), 0.0, 1.0) : 0.5 * (lo + hi);
    for (int it = 0; it < 60; ++it) {
        const double f = glm::dot(sigma, segment_column(s, t)) - tau;
        if (f > 0.0)
            hi = t;
        else
            lo = t;
        const double df = glm::dot(sigma, densities(s.o + t * s.v));
        double next = df > 0.0 ? t - f / df : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - t) <= 1e-9 * (1.0 + std::abs(t)) || hi - lo <= 1e-9 * (1.0 + hi)) return next;
        t = next;
    }
    return t;
}

glm::dvec3 ReferenceIntegrator::column_density(double r, double mu, double length) const {
    const double m = std::clamp(mu, -1.0, 1.0);
    const glm::dvec3 o(0.0, 0.0, r);
    const glm::dvec3 v(std::sqrt(std::max(0.0, (1.0 - m) * (1.0 + m))), 0.0, m);
    return make_segment(o, v, length, settings_.panel_height_m, {}).cum.back();
}

std::vector<double> ReferenceIntegrator::optical_depth(double r, double mu, double length) const {
    const glm::dvec3 d = column_density(r, mu, length);
    std::vector<double> tau(beta_r_.size());
    for (std::size_t k = 0; k < tau.size(); ++k) tau[k] = beta_r_[k] * d.x + beta_me_[k] * d.y + beta_o_[k] * d.z;
    return tau;
}

std::vector<double> ReferenceIntegrator::transmittance(double r, double mu) const {
    const double rc = std::clamp(r, params_.bottom_radius, params_.top_radius);
    auto tau = optical_depth(rc, mu, f64::ray_shell_exit_m(rc, mu, params_.bottom_radius, params_.top_radius));
    for (double& x : tau) x = std::exp(-x);
    return tau;
}

void ReferenceIntegrator::sun_transmittance(const glm::dvec3& p, const glm::dvec3& sun, double panel_h,
                                            std::vector<double>& out) const {
    out.assign(beta_r_.size(), 0.0);
    const double r = std::clamp(glm::length(p), params_.bottom_radius, params_.top_radius);
    const double mu_s = glm::dot(p, sun) / std::max(glm::length(p), 1e-300);
    if (f64::ray_hits_sphere(r, mu_s, params_.bottom_radius)) return;
    const Segment s = make_segment(p, sun, f64::ray_sphere_far_m(r, mu_s, params_.top_radius), panel_h, {});
    const glm::dvec3 d = s.cum.back();
    for (std::size_t k = 0; k < out.size(); ++k)
        out[k] = std::exp(-(beta_r_[k] * d.x + beta_me_[k] * d.y + beta_o_[k] * d.z));
}

void ReferenceIntegrator::single_scattering(const glm::dvec3& o, const glm::dvec3& v, double length, bool hits_ground,
                                            const glm::dvec3& sun, SkyRadiance& out) const {
    const std::size_t n = beta_r_.size();
    out.single_spectrum.assign(n, 0.0);
    out.ground_spectrum.assign(n, 0.0);
    // Split where the ray crosses the shadow cylinder |p - (p.s) s| = R (sunlit/shadowed boundary).
    std::vector<double> splits;
    {
        const double vs = glm::dot(v, sun), os = glm::dot(o, sun);
        const double A = 1.0 - vs * vs;
        const double B = 2.0 * (glm::dot(o, v) - os * vs);
        const double C = glm::dot(o, o) - os * os - params_.bottom_radius * params_.bottom_radius;
        const double disc = B * B - 4.0 * A * C;
        if (A > 1e-14 && disc >= 0.0) {
            const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
            splits.push_back(q / A);
            if (q != 0.0) splits.push_back(C / q);
        }
    }
    const Segment s = make_segment(o, v, length, settings_.panel_height_m, splits);
    const double nu = glm::dot(v, sun);
    const double pr = rayleigh_phase(nu), pm = cornette_shanks_phase(params_.mie_g, nu);
    std::vector<double> ts;
    for (std::size_t i = 1; i < s.t.size(); ++i) {
        const double a = s.t[i - 1], half = 0.5 * (s.t[i] - a), mid = a + half;
        if (half <= 0.0) continue;
        for (int k = 0; k < 5; ++k) {
            const double t = mid + half * kGlX[k];
            const glm::dvec3 p = o + t * v;
            const glm::dvec3 rho = densities(p);
            if (rho.x <= 0.0 && rho.y <= 0.0) continue;
            sun_transmittance(p, sun, settings_.panel_height_m, ts);
            const glm::dvec3 col = segment_column(s, t);
            const double w = kGlW[k] * half;
            for (std::size_t j = 0; j < n; ++j) {
                if (ts[j] <= 0.0) continue;
                const double tv = std::exp(-(beta_r_[j] * col.x + beta_me_[j] * col.y + beta_o_[j] * col.z));
                out.single_spectrum[j] +=
                    w * tv * ts[j] * sun_[j] * (beta_r_[j] * rho.x * pr + beta_ms_[j] * rho.y * pm);
            }
        }
    }
    if (hits_ground) {
        const glm::dvec3 g = o + length * v;
        const glm::dvec3 normal = glm::normalize(g);
        const double mu_s = glm::dot(normal, sun);
        if (mu_s > 0.0) {
            sun_transmittance(normal * params_.bottom_radius, sun, settings_.panel_height_m, ts);
            const glm::dvec3 col = s.cum.back();
            for (std::size_t j = 0; j < n; ++j) {
                const double tv = std::exp(-(beta_r_[j] * col.x + beta_me_[j] * col.y + beta_o_[j] * col.z));
                out.ground_spectrum[j] = tv * albedo_[j] / kPi * mu_s * ts[j] * sun_[j];
            }
        }
    }
}

// One Monte Carlo path of multiple_scattering(): its random stream, the current point and
// direction, and per wavelength the path throughput, the radiance collected so far and scratch
// space (the segment's optical depth, the transmittance toward the Sun).
struct ReferenceIntegrator::MsPath {
    Rng rng{0, 0};
    glm::dvec3 p{0.0}, w{0.0};
    std::vector<double> contrib, thr, tau, ts;
    std::vector<double> node, cdf;  // the line sample's density over the segment's panels
};

namespace {

// Running sums of the paths' radiance (spectrum, rgb, luminance): the mean and its standard error.
struct MsTally {
    explicit MsTally(std::size_t n) : sum(n, 0.0), sumsq(n, 0.0) {}

    void add(const std::vector<double>& contrib, const SpectralToColor& color) {
        for (std::size_t k = 0; k < contrib.size(); ++k) {
            sum[k] += contrib[k];
            sumsq[k] += contrib[k] * contrib[k];
        }
        const glm::dvec3 c = color.rgb(contrib);
        const double l = color.luminance(contrib);
        rgb_sum += c;
        rgb_sumsq += c * c;
        lum_sum += l;
        lum_sumsq += l * l;
    }

    // Mean and standard error of the luminance after m paths.
    std::pair<double, double> luminance(double m) const {
        const double mean = lum_sum / m;
        const double var = m < 2.0 ? 0.0 : std::max(0.0, (lum_sumsq - m * mean * mean) / (m - 1.0));
        return {mean, std::sqrt(var / m)};
    }

    void finish(double m, SkyRadiance& out) const {
        auto stderr_of = [m](double s, double s2) {
            if (m < 2.0) return 0.0;
            const double mean = s / m;
            return std::sqrt(std::max(0.0, (s2 - m * mean * mean) / (m - 1.0)) / m);
        };
        for (std::size_t k = 0; k < sum.size(); ++k) {
            out.multiple_spectrum[k] = sum[k] / m;
            out.multiple_stderr[k] = stderr_of(sum[k], sumsq[k]);
        }
        out.multiple_rgb = rgb_sum / m;
        out.multiple_rgb_stderr = {stderr_of(rgb_sum.x, rgb_sumsq.x), stderr_of(rgb_sum.y, rgb_sumsq.y),
                                   stderr_of(rgb_sum.z, rgb_sumsq.z)};
        out.multiple_luminance = lum_sum / m;
        out.multiple_luminance_stderr = stderr_of(lum_sum, lum_sumsq);
    }

    std::vector<double> sum, sumsq;
    glm::dvec3 rgb_sum{0.0}, rgb_sumsq{0.0};
    double lum_sum = 0.0, lum_sumsq = 0.0;
};

}  // namespace

void ReferenceIntegrator::multiple_scattering(const glm::dvec3& camera, const glm::dvec3& view, double length,
                                              bool hits_ground, const glm::dvec3& sun, SkyRadiance& out) const {
    const std::size_t n = beta_r_.size();
    const int max_order = settings_.scattering_orders;
    const int first = settings_.ms_first_order;
    const int paths = std::max(settings_.ms_paths, 0);
    out.multiple_spectrum.assign(n, 0.0);
    out.multiple_stderr.assign(n, 0.0);
    out.ms_paths = 0;
    if (max_order < first || paths == 0) return;

    MsTally tally(n);
    MsPath path;
    path.contrib.resize(n);
    path.thr.resize(n);
    path.tau.resize(n);
    path.ts.resize(n);
    // Adaptive count: the part computed by quadrature counts in the luminance the target refers to.
    const double fixed_lum = first == 1 ? 0.0 : out.single_luminance + out.ground_luminance;
    const int cap = std::max(paths, settings_.ms_max_paths);
    int done = 0;
    for (int batch = paths;; batch = std::min(cap, 2 * batch)) {
        for (int i = done; i < batch; ++i) {
            path.rng = Rng(settings_.seed, static_cast<std::uint64_t>(i));
            std::fill(path.contrib.begin(), path.contrib.end(), 0.0);
            std::fill(path.thr.begin(), path.thr.end(), 1.0);
            path.p = camera;
            path.w = view;
            trace_ms_path(path, length, hits_ground, sun);
            tally.add(path.contrib, color_);
        }
        done = batch;
        if (done >= cap) break;
        const auto [mean, err] = tally.luminance(static_cast<double>(done));
        if (err <= settings_.ms_target_noise * std::max(fixed_lum + mean, settings_.ms_target_floor)) break;
    }
    out.ms_paths = done;
    tally.finish(static_cast<double>(done), out);
}

void ReferenceIntegrator::trace_ms_path(MsPath& path, double length, bool hits_ground, const glm::dvec3& sun) const {
    const std::size_t n = beta_r_.size();
    const double R = params_.bottom_radius, top = params_.top_radius;
    const double inv_n = 1.0 / static_cast<double>(n);
    std::vector<double>& tau = path.tau;
    for (int order = 1; order <= settings_.scattering_orders; ++order) {
        const double r = glm::length(path.p);
        const double mu = glm::dot(path.p, path.w) / r;
        // The view ray keeps the ground decision and length sky() made for it (one decision per
        // ray, so rounding near the horizon cannot flip it); later segments decide from their own
        // origin.
        const bool ground = order == 1 ? hits_ground : f64::ray_hits_sphere(r, mu, R);
        const double len = order == 1 ? length
                           : ground   ? f64::ray_sphere_near_m(r, mu, R)
                                      : f64::ray_sphere_far_m(std::min(r, top), mu, top);
        const Segment s = make_segment(path.p, path.w, len, settings_.ms_panel_height_m, {});
        const glm::dvec3 dl = s.cum.back();
        for (std::size_t k = 0; k < n; ++k) tau[k] = beta_r_[k] * dl.x + beta_me_[k] * dl.y + beta_o_[k] * dl.z;
        const std::size_t hero = std::min(n - 1, static_cast<std::size_t>(path.rng.uniform() * static_cast<double>(n)));
        const glm::dvec3 sig_h(beta_r_[hero], beta_me_[hero], beta_o_[hero]);
        // Segments ending on the ground: choose the ground with probability alpha (the mean
        // transmittance, kept in [0.05, 0.95] so that neither branch becomes a rare event, e.g.
        // a camera 1 m above the ground looking down); otherwise, and on segments that leave
        // the atmosphere, a collision is forced inside [0, len].
        double alpha = 0.0;
        if (ground) {
            for (std::size_t k = 0; k < n; ++k) alpha += std::exp(-tau[k]);
            alpha = std::clamp(alpha * inv_n, 0.05, 0.95);
        }
        const bool lit_segment = settings_.ms_estimator == MsEstimator::kLitSegment;
        if (lit_segment && order >= settings_.ms_first_order) ms_lit_segment_nee(path, s, sun);
        const bool surface = ground && path.rng.uniform() < alpha;
        const double u = path.rng.uniform();
        if (lit_segment && !surface && order == settings_.scattering_orders) break;  // nothing left to collect
        if (surface) {
            if (!ms_surface_bounce(path, order, len, alpha, sun)) break;
            continue;
        }
        if (!(tau[hero] > 0.0)) break;
        const double target = -std::log1p(u * std::expm1(-tau[hero]));  // truncated to [0, tau]
        const double t = sample_segment(s, sig_h, std::min(target, tau[hero]));
        if (!ms_volume_scatter(path, order, s, t, alpha, sun)) break;
    }
}

bool ReferenceIntegrator::ms_surface_bounce(MsPath& path, int order, double len, double alpha,
                                            const glm::dvec3& sun) const {
    const std::size_t n = beta_r_.size();
    for (std::size_t k = 0; k < n; ++k) path.thr[k] *= std::exp(-path.tau[k]) / alpha;
    const glm::dvec3 normal = glm::normalize(path.p + len * path.w);
    path.p = normal * params_.bottom_radius;
    const double mu_s = glm::dot(normal, sun);
    if (order >= settings_.ms_first_order && mu_s > 0.0) {
        sun_transmittance(path.p, sun, settings_.ms_panel_height_m, path.ts);
        for (std::size_t k = 0; k < n; ++k)
            path.contrib[k] += path.thr[k] * albedo_[k] / kPi * mu_s * path.ts[k] * sun_[k];
    }
    if (order == settings_.scattering_orders) return false;
    // Cosine-weighted hemisphere (f cos / pdf = albedo), mixed with the twilight lobe in shadow.
    glm::dvec3 axis(0.0);
    const bool lobe = ms_twilight_axis(path.p, sun, axis);
    const double share = lobe ? kTwilightLobeShare : 0.0;
    const double u0 = lobe ? path.rng.uniform() : 1.0, u1 = path.rng.uniform(), u2 = path.rng.uniform();
    const glm::dvec3 w_new = u0 < share ? direction_around(axis, sample_hg_nu(kTwilightLobeG, u1), 2.0 * kPi * u2)
                                        : direction_around(normal, std::sqrt(1.0 - u1), 2.0 * kPi * u2);
    const double cos_n = glm::dot(normal, w_new);
    if (!(cos_n > 0.0)) return false;  // a lobe direction into the ground: f = 0
    const double pdf = (1.0 - share) * cos_n / kPi +
                       (lobe ? share * henyey_greenstein_phase(kTwilightLobeG, glm::dot(axis, w_new)) : 0.0);
    for (std::size_t k = 0; k < n; ++k) path.thr[k] *= albedo_[k] * (cos_n / kPi) / pdf;
    path.w = w_new;
    return true;
}

bool ReferenceIntegrator::ms_twilight_axis(const glm::dvec3& x, const glm::dvec3& sun, glm::dvec3& axis) const {
    if (settings_.ms_estimator != MsEstimator::kLitSegment) return false;
    const double len = glm::length(x);
    const double mu_s = glm::dot(x, sun) / std::max(len, 1e-300);
    if (!f64::ray_hits_sphere(std::clamp(len, params_.bottom_radius, params_.top_radius), mu_s, params_.bottom_radius))
        return false;  // sunlit: the phase function (or cosine) alone
    const glm::dvec3 off_axis = x - glm::dot(x, sun) * sun;
    const double d = glm::length(off_axis);
    if (!(d > 0.0)) return false;
    const glm::dvec3 target = (params_.bottom_radius + kTwilightAltitude_m) / d * off_axis;
    const glm::dvec3 to = target - x;
    if (!(glm::length(to) > 0.0)) return false;
    axis = glm::normalize(to);
    return true;
}

bool ReferenceIntegrator::ms_volume_scatter(MsPath& path, int order, const Segment& s, double t, double alpha,
                                            const glm::dvec3& sun) const {
    const std::size_t n = beta_r_.size();
    const double inv_n = 1.0 / static_cast<double>(n);
    const double g = params_.mie_g;
    const std::vector<double>& tau = path.tau;
    std::vector<double>& thr = path.thr;
    const glm::dvec3 x = path.p + t * path.w;
    const glm::dvec3 col = segment_column(s, t);
    const glm::dvec3 rho = densities(x);
    double pdf = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        const double tk = beta_r_[k] * col.x + beta_me_[k] * col.y + beta_o_[k] * col.z;
        const double sk = beta_r_[k] * rho.x + beta_me_[k] * rho.y + beta_o_[k] * rho.z;
        const double norm = -std::expm1(-tau[k]);
        if (norm > 0.0) pdf += sk * std::exp(-tk) / norm;
    }
    pdf *= inv_n * (1.0 - alpha);
    if (!(pdf > 0.0)) return false;
    for (std::size_t k = 0; k < n; ++k) {
        const double tk = beta_r_[k] * col.x + beta_me_[k] * col.y + beta_o_[k] * col.z;
        thr[k] *= std::exp(-tk) / pdf;
    }
    path.p = x;
    if (settings_.ms_estimator == MsEstimator::kCollision && order >= settings_.ms_first_order) {
        sun_transmittance(path.p, sun, settings_.ms_panel_height_m, path.ts);
        const double nu = glm::dot(path.w, sun);
        const double pr = rayleigh_phase(nu), pm = cornette_shanks_phase(g, nu);
        for (std::size_t k = 0; k < n; ++k)
            path.contrib[k] += thr[k] * (beta_r_[k] * rho.x * pr + beta_ms_[k] * rho.y * pm) * path.ts[k] * sun_[k];
    }
    if (order == settings_.scattering_orders) return false;
    // New direction from the Rayleigh / HG mixture.
    double sr = 0.0, sm = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        sr += beta_r_[k] * rho.x;
        sm += beta_ms_[k] * rho.y;
    }
    if (!(sr + sm > 0.0)) return false;
    const double q = sr / (sr + sm);
    glm::dvec3 axis(0.0);
    const bool lobe = ms_twilight_axis(path.p, sun, axis);
    const double share = lobe ? kTwilightLobeShare : 0.0;
    const double u0 = lobe ? path.rng.uniform() : 1.0;
    const double u1 = path.rng.uniform(), u2 = path.rng.uniform(), u3 = path.rng.uniform();
    glm::dvec3 w_new;
    if (u0 < share) {
        w_new = direction_around(axis, sample_hg_nu(kTwilightLobeG, u2), 2.0 * kPi * u3);
    } else {
        const double nu = u1 < q ? sample_rayleigh_nu(u2) : sample_hg_nu(g, u2);
        w_new = direction_around(path.w, nu, 2.0 * kPi * u3);
    }
    const double c = glm::dot(path.w, w_new);
    const double dir_pdf = (1.0 - share) * (q * rayleigh_phase(c) + (1.0 - q) * henyey_greenstein_phase(g, c)) +
                           (lobe ? share * henyey_greenstein_phase(kTwilightLobeG, glm::dot(axis, w_new)) : 0.0);
    if (!(dir_pdf > 0.0)) return false;
    const double pr = rayleigh_phase(c), pm = cornette_shanks_phase(g, c);
    for (std::size_t k = 0; k < n; ++k) thr[k] *= (beta_r_[k] * rho.x * pr + beta_ms_[k] * rho.y * pm) / dir_pdf;
    path.w = w_new;
    return true;
}

void ReferenceIntegrator::ms_lit_segment_nee(MsPath& path, const Segment& s, const glm::dvec3& sun) const {
    // Bound of the in-scattered sunlight at the panel boundaries, at one wavelength.
    const std::size_t m = s.t.size(), k = proxy_k_;
    const glm::dvec3 sigma(beta_r_[k], beta_me_[k], beta_o_[k]);
    path.node.resize(m);
    double peak = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
        const glm::dvec3 x = s.o + s.t[i] * s.v;
        const glm::dvec3 rho = densities(x);
        const double scatter = beta_r_[k] * rho.x + beta_ms_[k] * rho.y;
        path.node[i] = scatter > 0.0 ? scatter * std::exp(-glm::dot(sigma, s.cum[i])) * sun_proxy(x, sun) : 0.0;
        peak = std::max(peak, path.node[i]);
    }
    // Piecewise-constant density over the panels: the larger end of each (the shadow is convex, so
    // a panel with a sunlit point has a sunlit end), plus 1e-3 of the peak everywhere.
    path.cdf.assign(m, 0.0);
    for (std::size_t i = 1; i < m; ++i)
        path.cdf[i] =
            path.cdf[i - 1] + (s.t[i] - s.t[i - 1]) * (std::max(path.node[i - 1], path.node[i]) + 1e-3 * peak);
    const double total = path.cdf.back(), u = path.rng.uniform();
    if (!(s.length > 0.0)) return;
    if (!(total > 0.0)) {  // no sunlit air, or none the proxy sees: uniform in distance
        ms_add_sunlight(path, s, u * s.length, s.length, sun);
        return;
    }
    const double target = u * total;
    std::size_t i =
        static_cast<std::size_t>(std::upper_bound(path.cdf.begin() + 1, path.cdf.end(), target) - path.cdf.begin());
    i = std::clamp<std::size_t>(i, 1, m - 1);
    const double w = path.cdf[i] - path.cdf[i - 1], width = s.t[i] - s.t[i - 1];
    if (!(w > 0.0) || !(width > 0.0)) return;
    const double t = s.t[i - 1] + std::clamp((target - path.cdf[i - 1]) / w, 0.0, 1.0) * width;
    ms_add_sunlight(path, s, t, total * width / w, sun);  // 1 / pdf(t)
}

void ReferenceIntegrator::ms_add_sunlight(MsPath& path, const Segment& s, double t, double weight,
                                          const glm::dvec3& sun) const {
    const glm::dvec3 x = s.o + t * s.v;
    const glm::dvec3 rho = densities(x);
    if (rho.x <= 0.0 && rho.y <= 0.0) return;
    sun_transmittance(x, sun, settings_.ms_panel_height_m, path.ts);
    const glm::dvec3 col = segment_column(s, t);
    const double nu = glm::dot(s.v, sun);
    const double pr = rayleigh_phase(nu), pm = cornette_shanks_phase(params_.mie_g, nu);
    for (std::size_t k = 0; k < path.contrib.size(); ++k) {
        if (path.ts[k] <= 0.0) continue;
        const double tv = std::exp(-(beta_r_[k] * col.x + beta_me_[k] * col.y + beta_o_[k] * col.z));
        path.contrib[k] +=
            weight * path.thr[k] * tv * (beta_r_[k] * rho.x * pr + beta_ms_[k] * rho.y * pm) * path.ts[k] * sun_[k];
    }
}

SkyRadiance ReferenceIntegrator::sky(const SkyQuery& q) const {
    const std::size_t n = beta_r_.size();
    SkyRadiance out;
    out.spectrum.assign(n, 0.0);
    out.single_spectrum.assign(n, 0.0);
    out.ground_spectrum.assign(n, 0.0);
    out.multiple_spectrum.assign(n, 0.0);
    out.multiple_stderr.assign(n, 0.0);
    const double R = params_.bottom_radius, top = params_.top_radius;
    const double deg = kPi / 180.0;
    const double tv = q.view_zenith_deg * deg, ts = q.sun_zenith_deg * deg, phi = q.relative_azimuth_deg * deg;
    const glm::dvec3 view(std::sin(tv), 0.0, std::cos(tv));
    const glm::dvec3 sun(std::sin(ts) * std::cos(phi), std::sin(ts) * std::sin(phi), std::cos(ts));
    const double r_cam = std::max(R + q.altitude_m, R + kMinCameraAltitude);
    const RayEntry e = enter_atmosphere(r_cam, view.z, R, top);
    if (!e.intersects) {
        out.in_atmosphere = false;
        return out;
    }
    const glm::dvec3 o = glm::dvec3(0.0, 0.0, r_cam) + e.offset_m * view;
    out.hits_ground = f64::ray_hits_sphere(e.r_m, e.mu, R);
    const double length =
        out.hits_ground ? f64::ray_sphere_near_m(e.r_m, e.mu, R) : f64::ray_sphere_far_m(e.r_m, e.mu, top);
    single_scattering(o, view, length, out.hits_ground, sun, out);
    out.single_luminance = color_.luminance(out.single_spectrum);
    out.ground_luminance = color_.luminance(out.ground_spectrum);
    multiple_scattering(o, view, length, out.hits_ground, sun, out);
    for (std::size_t k = 0; k < n; ++k)
        out.spectrum[k] = settings_.ms_first_order == 1
                              ? out.multiple_spectrum[k]
                              : out.single_spectrum[k] + out.ground_spectrum[k] + out.multiple_spectrum[k];
    out.xyz = color_.xyz(out.spectrum);
    out.rgb = xyz_to_linear_srgb(out.xyz);
    out.luminance = out.xyz.y;
    return out;
}

}  // namespace cupola::atmosphere

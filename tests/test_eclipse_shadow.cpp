// Eclipse shadows: the double-precision reference (common/eclipse/eclipse_reference) against
// closed forms and a second integration, the shared functions of shaders/shared/eclipse_shadow.glsl
// (C++ float build) against the reference, the numerically hard geometries, and the GPU build of
// the same text against the C++ build.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "eclipse/eclipse_reference.hpp"
#include "gl/egl_context.hpp"
#include "gl/gl_api.hpp"
#include "gl/gl_buffer.hpp"
#include "gl/gl_framebuffer.hpp"
#include "gl/gl_program.hpp"
#include "gl/gl_texture.hpp"
#include "shading/shared_shading.hpp"

using namespace cupola;
namespace sh = cupola::shading;
using eclipse::visible_fraction_reference;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kU = 0.6f;                       // the Sun's limb darkening in the scenes
constexpr double kUlp1 = 1.1920928955078125e-7;  // float spacing just above 1 (2 ulps below)

// Overlap area of the unit disc and a disc of radius a at distance s, in a well-conditioned
// form: the half-chord y0 at the radical line from Kahan's triangle area (sides 1, a, s), both
// segment angles through atan2 (no acos near +-1).
double lens_area(double a, double s) {
    if (s >= 1.0 + a) return 0.0;
    if (s <= std::fabs(1.0 - a)) return kPi * std::pow(std::min(1.0, a), 2);
    double p = 1.0, q = a, r = s;  // sorted p >= q >= r
    if (q > p) std::swap(p, q);
    if (r > q) std::swap(q, r);
    if (q > p) std::swap(p, q);
    const double area = 0.25 * std::sqrt((p + (q + r)) * (r - (p - q)) * (r + (p - q)) * (p + (q - r)));
    const double y0 = 2.0 * area / s;
    const double x0 = (a < 2.0 ? (1.0 - a) * (1.0 + a) + s * s : 1.0 + (s - a) * (s + a)) / (2.0 * s);
    return std::atan2(y0, x0) - x0 * y0 + a * a * std::atan2(y0, s - x0) - (s - x0) * y0;
}

// Flux of the limb-darkened unit disc inside radius c (closed form).
double disc_flux(double c, double u) {
    const double m = (1.0 - c) * (1.0 + c);
    return kPi * (1.0 - u) * c * c + u * (2.0 * kPi / 3.0) * (1.0 - m * std::sqrt(m));
}

double intensity(double r, double u) { return 1.0 - u * (1.0 - std::sqrt(std::max(0.0, (1.0 - r) * (1.0 + r)))); }

// A second, different integration for cross-checking the reference: rings about the Sun's
// centre (what the shader does, but in double with 640 nodes): core closed form plus
// integral I(r) 2 r theta(r) dr, r = lo + w sin^2(phi/2), composite 10-point Gauss-Legendre on 64
// panels in phi.
double rings_about_the_sun(double a, double s, double u) {
    if (s >= 1.0 + a) return 1.0;
    double occluded = disc_flux(std::clamp(a - s, 0.0, 1.0), u);
    const double lo = std::fabs(s - a), hi = std::min(1.0, s + a);
    if (hi > lo && s > 0.0) {
        static const double x[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244, 0.8650633666889845,
                                    0.9739065285171717};
        static const double w[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820, 0.1494513491505806,
                                    0.0666713443086881};
        const int panels = 64;
        const double h = kPi / panels;
        double ring = 0.0;
        for (int p = 0; p < panels; ++p)
            for (int i = 0; i < 5; ++i)
                for (int sign : {-1, 1}) {
                    const double phi = h * (p + 0.5 + 0.5 * sign * x[i]);
                    const double r = lo + (hi - lo) * std::pow(std::sin(0.5 * phi), 2);
                    const double dr = (hi - lo) * 0.5 * std::sin(phi);
                    const double c = ((r - a) * (r + a) + s * s) / (2.0 * r * s);
                    ring += 0.5 * h * w[i] * intensity(r, u) * 2.0 * r * std::acos(std::clamp(c, -1.0, 1.0)) * dr;
                }
        occluded += ring;
    }
    return 1.0 - occluded / disc_flux(1.0, u);
}

// (a, s) over a dense grid: log2 a in [lmin, lmax], s from 0 to 1.1 (1 + a), plus the contacts.
std::vector<std::pair<float, float>> dense_grid(double lmin, double lmax, int na, int ns) {
    std::vector<std::pair<float, float>> g;
    for (int i = 0; i <= na; ++i) {
        const double a = std::exp2(lmin + (lmax - lmin) * i / na);
        for (int k = 0; k <= ns; ++k)
            g.emplace_back(static_cast<float>(a), static_cast<float>(1.1 * (1.0 + a) * k / ns));
        for (double c : {std::fabs(1.0 - a), a, 1.0 + a}) g.emplace_back(static_cast<float>(a), static_cast<float>(c));
    }
    return g;
}

std::string sci(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", v);
    return b;
}

struct ErrorStats {
    double max = 0.0, sum = 0.0;
    long n = 0;
    float worst_a = 0.0f, worst_s = 0.0f;
    void add(double e, float a, float s) {
        sum += e;
        ++n;
        if (e > max) max = e, worst_a = a, worst_s = s;
    }
    double mean() const { return n ? sum / n : 0.0; }
    std::string where() const { return "a=" + std::to_string(worst_a) + " s=" + std::to_string(worst_s); }
};

const sh::Texture2DData& default_lut() {
    static const sh::Texture2DData t =
        eclipse::build_eclipse_lut(kU, eclipse::kEclipseLutWidth, eclipse::kEclipseLutHeight);
    return t;
}
sh::vec2 default_lut_size() { return sh::vec2(eclipse::kEclipseLutWidth, eclipse::kEclipseLutHeight); }
float lut_visible(float a, float s) {
    return sh::eclipse_visible_lut(sh::sampler2D{&default_lut()}, default_lut_size(), a, s);
}

// The discs seen from a point in double: a and s from double vectors (the all-double path).
struct DiscsD {
    double ratio, separation;
};
DiscsD discs_double(const glm::dvec3& to_sun, double sun_radius, const glm::dvec3& to_caster, double caster_radius) {
    const double ds = glm::length(to_sun), dc = glm::length(to_caster);
    const double rs = std::asin(sun_radius / ds), rc = std::asin(caster_radius / dc);
    const double sep = 2.0 * std::asin(0.5 * glm::length(to_sun / ds - to_caster / dc));
    return {rc / rs, sep / rs};
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The reference against closed forms.

TEST(EclipseReference, UniformDiscIsTheCircleIntersectionArea) {
    ErrorStats st;
    for (int i = 0; i <= 96; ++i) {
        const double a = std::exp2(-12.0 + 24.0 * i / 96);
        for (int k = 0; k <= 200; ++k) {
            const double s = (1.0 + a) * k / 200;
            st.add(std::fabs(visible_fraction_reference(a, s, 0.0) - (1.0 - lens_area(a, s) / kPi)), a, s);
        }
        for (double s : {std::fabs(1.0 - a), a, 1.0 + a, std::fabs(1.0 - a) * (1 + 1e-9) + 1e-12})
            st.add(std::fabs(visible_fraction_reference(a, s, 0.0) - (1.0 - lens_area(a, s) / kPi)), a, s);
    }
    RecordProperty("max_abs_error", sci(st.max));
    std::printf("reference (u = 0) vs lens area: max %.3g (%s) over %ld points\n", st.max, st.where().c_str(), st.n);
    EXPECT_LT(st.max, 1e-12) << st.where();
}

TEST(EclipseReference, ConcentricDiscsAndFullCoverAreClosedForm) {
    for (double u : {0.0, 0.3, 0.6, 1.0})
        for (double a : {1e-4, 0.01, 0.3, 0.9, 0.99, 0.999999, 1.0}) {
            const double expected = 1.0 - disc_flux(a, u) / disc_flux(1.0, u);
            EXPECT_NEAR(visible_fraction_reference(a, 0.0, u), expected, 1e-13) << "a=" << a << " u=" << u;
            // Annular with the occluder's disc wholly inside: same flux as the core closed form
            // when it sits at the centre, any s < 1 - a moves it over dimmer limb (more light left).
            if (a < 0.9) {
                EXPECT_GT(visible_fraction_reference(a, 0.5 * (1.0 - a), u), expected - 1e-15);
            }
        }
    for (double u : {0.0, 0.6, 1.0}) {
        EXPECT_EQ(visible_fraction_reference(1.0, 0.0, u), 0.0);
        EXPECT_EQ(visible_fraction_reference(1.5, 0.3, u), 0.0);     // totality
        EXPECT_EQ(visible_fraction_reference(100.0, 99.0, u), 0.0);  // second contact of a huge caster
        EXPECT_EQ(visible_fraction_reference(0.5, 1.5, u), 1.0);     // first contact
        EXPECT_EQ(visible_fraction_reference(0.5, 7.0, u), 1.0);
        EXPECT_EQ(visible_fraction_reference(0.5, -7.0, u), 1.0);  // a negative s counts as |s|
    }
}

TEST(EclipseReference, TinyOccluderDarkensByItsAreaTimesTheLocalIntensity) {
    // 1 - V = a^2 <I>_disc / (1 - u/3); the mean of I over the small disc is
    // I(s) + (a^2 / 8) laplacian I(s) + O(a^4), laplacian sqrt(1 - r^2) = -(2 - r^2) / (1 - r^2)^(3/2).
    // At the centre the first term alone is a^2 I(0) / (1 - u/3).
    const double a = 1e-3;
    for (double u : {0.0, 0.6, 1.0}) {
        EXPECT_NEAR((1.0 - visible_fraction_reference(a, 0.0, u)) / (a * a / (1.0 - u / 3.0)), 1.0, 1e-6) << u;
        for (double s : {0.0, 0.3, 0.6, 0.9, 0.99}) {
            const double darkening = 1.0 - visible_fraction_reference(a, s, u);
            const double laplacian = -(2.0 - s * s) / std::pow(1.0 - s * s, 1.5);
            const double expected = a * a * (intensity(s, u) + u * a * a / 8.0 * laplacian) / (1.0 - u / 3.0);
            // 1e-9 up to s = 0.9; at s = 0.99 the next (a^4) term still reaches 5e-7.
            EXPECT_NEAR(darkening / expected, 1.0, 1e-6) << "s=" << s << " u=" << u;
        }
    }
}

TEST(EclipseReference, AgreesWithRingsAboutTheSunsCentre) {
    // Different coordinates (polar about the Sun's centre), different quadrature, same answer.
    ErrorStats st;
    for (double u : {0.3, 0.6, 1.0})
        for (double a : {0.02, 0.3, 0.9, 0.97, 1.0, 1.03, 1.5, 3.7, 40.0})
            for (int k = 1; k < 40; ++k) {
                const double s = (1.0 + a) * k / 40;
                st.add(std::fabs(visible_fraction_reference(a, s, u) - rings_about_the_sun(a, s, u)), a, s);
            }
    RecordProperty("max_abs_difference", sci(st.max));
    std::printf("reference vs rings about the Sun's centre: max %.3g (%s) over %ld points\n", st.max,
                st.where().c_str(), st.n);
    EXPECT_LT(st.max, 1e-11) << st.where();
}

TEST(EclipseReference, ReportsItsErrorBoundAndRejectsBadInput) {
    for (double a : {1e-4, 0.5, 0.999, 1.0, 1.001, 3.7, 1e4})
        for (double t : {0.01, 0.5, 0.99}) {
            const double s = std::fabs(1.0 - a) + 2.0 * std::min(1.0, a) * t;
            const auto r = eclipse::visible_fraction_reference_detail(a, s, 0.6);
            EXPECT_LT(r.error_bound, 1e-13) << a << " " << s;
            EXPECT_GT(r.evaluations, 0);
            EXPECT_LT(r.evaluations, 200000);
        }
    EXPECT_THROW(visible_fraction_reference(0.0, 0.5, 0.6), std::invalid_argument);
    EXPECT_THROW(visible_fraction_reference(-1.0, 0.5, 0.6), std::invalid_argument);
    EXPECT_THROW(visible_fraction_reference(std::nan(""), 0.5, 0.6), std::invalid_argument);
    EXPECT_THROW(visible_fraction_reference(1.0, std::numeric_limits<double>::infinity(), 0.6), std::invalid_argument);
    EXPECT_THROW(visible_fraction_reference(1.0, 0.5, 1.5), std::invalid_argument);
    EXPECT_THROW(eclipse::build_eclipse_lut(0.6, 1, 8), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// The shared functions (C++ float build) against the reference.

TEST(EclipseShadow, EveryModeIsFiniteAndInRangeOnADenseGrid) {
    const auto grid = dense_grid(-10.0, 10.0, 160, 120);
    for (auto [a, s] : grid) {
        const float v[3] = {sh::eclipse_visible_exact(a, s, kU), sh::eclipse_visible_fast(a, s, 4.0f),
                            lut_visible(a, s)};
        for (int m = 0; m < 3; ++m) {
            ASSERT_TRUE(std::isfinite(v[m])) << "mode " << m << " a=" << a << " s=" << s;
            ASSERT_GE(v[m], 0.0f) << "mode " << m << " a=" << a << " s=" << s;
            ASSERT_LE(v[m], 1.0f) << "mode " << m << " a=" << a << " s=" << s;
        }
        const int region = sh::eclipse_region(a, s);
        ASSERT_GE(region, 0);
        ASSERT_LE(region, 3);
        if (s >= 1.0f + a) {
            ASSERT_EQ(v[0] + v[1] + v[2], 3.0f);  // beyond first contact: full sunlight
        }
    }
}

TEST(EclipseShadow, ExactMatchesTheReference) {
    ErrorStats st;
    for (auto [a, s] : dense_grid(-10.0, 10.0, 160, 120))
        st.add(std::fabs(sh::eclipse_visible_exact(a, s, kU) - visible_fraction_reference(a, s, kU)), a, s);
    for (float u : {0.0f, 1.0f})
        for (auto [a, s] : dense_grid(-3.0, 3.0, 24, 40))
            st.add(std::fabs(sh::eclipse_visible_exact(a, s, u) - visible_fraction_reference(a, s, u)), a, s);
    RecordProperty("max_abs_error", sci(st.max));
    RecordProperty("mean_abs_error", sci(st.mean()));
    std::printf("exact vs reference: max %.3g (%s), mean %.3g over %ld points\n", st.max, st.where().c_str(), st.mean(),
                st.n);
    EXPECT_LT(st.max, 1e-6) << st.where();  // measured 2.4e-7: float rounding of 1 - occluded / total
    EXPECT_LT(st.mean(), 1e-7);
}

TEST(EclipseShadow, LookupTableLayoutAndErrorBound) {
    const sh::Texture2DData& t = default_lut();
    const sh::vec2 size = default_lut_size();
    // Texel centres map back onto themselves; the table holds the reference there.
    for (int j = 0; j < t.height; j += 4)
        for (int i = 0; i < t.width; i += 4) {
            const sh::vec2 xy(static_cast<float>(i) / (t.width - 1), static_cast<float>(j) / (t.height - 1));
            const sh::vec2 as = sh::eclipse_lut_parameters(xy);
            const sh::vec2 uv = sh::eclipse_lut_coordinates(as.x, as.y, size);
            ASSERT_NEAR(uv.x * size.x - 0.5f, static_cast<float>(i), 2e-3f) << i << "," << j;
            if (as.x != 1.0f) {  // at a = 1 the rows below the contact row all stand for s = 0
                ASSERT_NEAR(uv.y * size.y - 0.5f, static_cast<float>(j), 2e-3f) << i << "," << j;
            }
            ASSERT_NEAR(t.at(i, j).r, visible_fraction_reference(as.x, as.y, kU), 1e-7) << i << "," << j;
        }
    // Column (w - 1) / 2 is a = 1; row (h - 1) / 8 is the inner contact.
    EXPECT_FLOAT_EQ(sh::eclipse_lut_parameters(sh::vec2(0.5f, 0.3f)).x, 1.0f);
    const sh::vec2 contact = sh::eclipse_lut_parameters(sh::vec2(0.25f, 0.125f));
    EXPECT_NEAR(contact.y, std::fabs(1.0f - contact.x), 1e-6f);

    ErrorStats sun_moon, earth_moon, all;
    for (int i = 0; i <= 100; ++i)
        for (int k = 0; k <= 200; ++k) {
            const float a = 0.9f + 0.2f * i / 100, s = (1.0f + a) * k / 200;
            sun_moon.add(std::fabs(lut_visible(a, s) - visible_fraction_reference(a, s, kU)), a, s);
        }
    for (int k = 0; k <= 1000; ++k) {
        const float a = 3.7f, s = (1.0f + a) * k / 1000;
        earth_moon.add(std::fabs(lut_visible(a, s) - visible_fraction_reference(a, s, kU)), a, s);
    }
    for (auto [a, s] : dense_grid(-6.0, 6.0, 240, 100))
        all.add(std::fabs(lut_visible(a, s) - visible_fraction_reference(a, s, kU)), a, s);
    for (const auto& [name, st] :
         {std::pair<const char*, ErrorStats&>{"sun_moon", sun_moon}, {"earth_moon", earth_moon}, {"all", all}}) {
        RecordProperty(std::string(name) + "_max", sci(st.max));
        RecordProperty(std::string(name) + "_mean", sci(st.mean()));
        std::printf("lut %dx%d %s: max %.3g (%s), mean %.3g\n", t.width, t.height, name, st.max, st.where().c_str(),
                    st.mean());
    }
    // Measured (65 x 65, u = 0.6): Sun-Moon 1.5e-3 / 8e-5, a = 3.7 4.8e-4 / 3e-5, all 1.2e-3 / 9e-5.
    EXPECT_LT(sun_moon.max, 2.5e-3) << sun_moon.where();
    EXPECT_LT(sun_moon.mean(), 2e-4);
    EXPECT_LT(earth_moon.max, 1e-3) << earth_moon.where();
    EXPECT_LT(earth_moon.mean(), 1e-4);
    EXPECT_LT(all.max, 2.5e-3) << all.where();
    // Outside the table's a range (2^+-6) the nearest column is used: still a sane value.
    for (float a : {1e-3f, 200.0f})
        for (float t01 : {0.2f, 0.5f, 0.8f}) {
            const float s = std::fabs(1.0f - a) + 2.0f * std::min(1.0f, a) * t01;
            EXPECT_NEAR(lut_visible(a, s), visible_fraction_reference(a, s, kU), 3e-3) << a << " " << s;
        }
}

TEST(EclipseShadow, FastModeIsTheSeedsLinearPenumbra) {
    // No accuracy bound (it is the approximation of Ekelin & Fernqvist 2009, section 3.3.2); its
    // error is reported, and it keeps the limits: 1 beyond first contact, 0 in the umbra, 1 - a^2
    // at the antumbra's centre.
    ErrorStats sun_moon;
    for (int i = 0; i <= 40; ++i)
        for (int k = 0; k <= 200; ++k) {
            const float a = 0.9f + 0.2f * i / 40, s = std::fabs(1.0f - a) + 2.0f * std::min(1.0f, a) * k / 200;
            sun_moon.add(std::fabs(sh::eclipse_visible_fast(a, s, 4.0f) - visible_fraction_reference(a, s, kU)), a, s);
        }
    RecordProperty("sun_moon_max", sci(sun_moon.max));
    RecordProperty("sun_moon_mean", sci(sun_moon.mean()));
    std::printf("fast (n = 4) vs reference, Sun-Moon penumbra: max %.3g (%s), mean %.3g\n", sun_moon.max,
                sun_moon.where().c_str(), sun_moon.mean());
    EXPECT_LT(sun_moon.mean(), 0.1);
    EXPECT_EQ(sh::eclipse_visible_fast(0.97f, 1.97f, 4.0f), 1.0f);
    EXPECT_EQ(sh::eclipse_visible_fast(1.03f, 0.01f, 4.0f), 0.0f);
    EXPECT_NEAR(sh::eclipse_visible_fast(0.5f, 0.0f, 4.0f), 0.75f, 1e-7f);
    float prev = 2.0f;
    for (int k = 400; k >= 0; --k) {
        const float v = sh::eclipse_visible_fast(0.97f, 2.0f * k / 400, 4.0f);
        EXPECT_LE(v, prev);
        prev = v;
    }
}

TEST(EclipseShadow, IllustrativeRegions) {
    EXPECT_EQ(sh::eclipse_region(1.03f, 0.02f), 0);  // umbra
    EXPECT_EQ(sh::eclipse_region(0.97f, 0.02f), 1);  // antumbra
    EXPECT_EQ(sh::eclipse_region(0.97f, 1.0f), 2);   // penumbra
    EXPECT_EQ(sh::eclipse_region(0.97f, 1.97f), 3);  // first contact: outside
    EXPECT_EQ(sh::eclipse_region(1.0f, 0.0f), 0);
    EXPECT_EQ(sh::eclipse_region_tint(3), sh::vec3(1.0f));
}

// ---------------------------------------------------------------------------------------------
// Numerically hard geometries.

namespace {

// Exact visible fractions along decreasing s must not increase by more than `slack` (float
// rounding of 1 - occluded / total where the true function is flat), must be finite and in
// [0, 1], and must match the reference within `tol`; fast and LUT must be monotone too.
void expect_monotone_and_accurate(float a, std::vector<float> s_values, double tol, double slack) {
    std::sort(s_values.begin(), s_values.end(), std::greater<float>());
    s_values.erase(std::unique(s_values.begin(), s_values.end()), s_values.end());
    float prev = 1.0f, prev_fast = 1.0f, prev_lut = 1.0f;
    double worst_increase = 0.0, worst_error = 0.0;
    for (float s : s_values) {
        // The fast and LUT modes are monotone by construction (no slack); finite, in [0, 1].
        const float fast = sh::eclipse_visible_fast(a, s, 4.0f), lut = lut_visible(a, s);
        ASSERT_TRUE(std::isfinite(fast) && fast >= 0.0f && fast <= 1.0f) << "a=" << a << " s=" << s;
        ASSERT_TRUE(std::isfinite(lut) && lut >= 0.0f && lut <= 1.0f) << "a=" << a << " s=" << s;
        EXPECT_LE(fast, prev_fast) << "a=" << a << " s=" << s;
        EXPECT_LE(lut, prev_lut + 1e-7f) << "a=" << a << " s=" << s;
        prev_fast = fast;
        prev_lut = lut;
        const float v = sh::eclipse_visible_exact(a, s, kU);
        ASSERT_TRUE(std::isfinite(v)) << "a=" << a << " s=" << s;
        ASSERT_GE(v, 0.0f) << "a=" << a << " s=" << s;
        ASSERT_LE(v, 1.0f) << "a=" << a << " s=" << s;
        EXPECT_LE(v, prev + slack) << "a=" << a << " s=" << s;
        worst_increase = std::max(worst_increase, static_cast<double>(v) - prev);
        const double e = std::fabs(v - visible_fraction_reference(a, s, kU));
        EXPECT_LT(e, tol) << "a=" << a << " s=" << s;
        worst_error = std::max(worst_error, e);
        prev = v;
    }
    std::printf("a=%g: %zu separations, largest increase %.3g, largest error %.3g\n", a, s_values.size(),
                worst_increase, worst_error);
}

std::vector<float> closing_separations(float a) {
    std::vector<float> s;
    for (int k = 0; k <= 2000; ++k) s.push_back((1.0f + a) * k / 2000);
    for (int e = 1; e <= 40; ++e) {  // 2^-1 .. 2^-40 and 1e-1 .. 1e-8 towards 0 and every contact
        for (float c : {0.0f, std::fabs(1.0f - a), 1.0f + a, a}) {
            for (float d : {std::ldexp(1.0f, -e), static_cast<float>(std::pow(10.0, -std::min(e, 8)))}) {
                s.push_back(c + d);
                if (c - d >= 0.0f) s.push_back(c - d);
            }
        }
    }
    for (float d : {1e-7f, 1e-5f, 1e-3f, std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min()})
        s.push_back(d);
    s.push_back(0.0f);
    s.push_back(std::nextafter(1.0f + a, 0.0f));
    s.push_back(std::nextafter(1.0f + a, 10.0f * a));
    return s;
}

}  // namespace

TEST(EclipseStability, NearlyEqualDiscsWithTheSeparationGoingToZero) {
    for (float a : {0.99f, 1.0f, 1.01f}) expect_monotone_and_accurate(a, closing_separations(a), 1e-6, 2 * kUlp1);
    EXPECT_EQ(sh::eclipse_visible_exact(1.0f, 0.0f, kU), 0.0f);
    EXPECT_EQ(sh::eclipse_visible_exact(1.01f, 0.0f, kU), 0.0f);
    EXPECT_EQ(sh::eclipse_visible_exact(1.01f, 1e-7f, kU), 0.0f);
    EXPECT_NEAR(sh::eclipse_visible_exact(0.99f, 0.0f, kU), 1.0 - disc_flux(0.99f, kU) / disc_flux(1.0, kU), 2e-7);
    EXPECT_NEAR(sh::eclipse_visible_exact(1.0f, 1e-5f, kU), visible_fraction_reference(1.0, 1e-5f, kU), 2e-7);
    EXPECT_GT(sh::eclipse_visible_exact(1.0f, 1e-5f, kU), 0.0f);  // a crescent of 1e-5 still shows
}

TEST(EclipseStability, TangentDiscs) {
    for (float a : {1e-3f, 0.25f, 0.5f, 0.97f, 0.99f, 1.01f, 2.0f, 3.7f, 100.0f}) {
        const float first = 1.0f + a;
        EXPECT_EQ(sh::eclipse_visible_exact(a, first, kU), 1.0f) << a;
        EXPECT_EQ(sh::eclipse_visible_exact(a, std::nextafter(first, 2.0f * first), kU), 1.0f) << a;
        const float just_inside = std::nextafter(first, 0.0f);
        EXPECT_LE(sh::eclipse_visible_exact(a, just_inside, kU), 1.0f) << a;
        EXPECT_NEAR(sh::eclipse_visible_exact(a, just_inside, kU), 1.0f, 2 * kUlp1) << a;
        EXPECT_EQ(lut_visible(a, first), 1.0f) << a;
        EXPECT_EQ(sh::eclipse_visible_fast(a, first, 4.0f), 1.0f) << a;
        // One ulp inside: the linear penumbra has moved by that ulp over its width (2 min(1, a)).
        EXPECT_NEAR(sh::eclipse_visible_fast(a, just_inside, 4.0f), 1.0f,
                    1e-6 + (first - just_inside) / (2.0f * std::min(1.0f, a)))
            << a;
        EXPECT_NEAR(lut_visible(a, just_inside), 1.0f, 1e-5f) << a;
        // Internal contact s = |1 - a| and its neighbours.
        const float inner = std::fabs(1.0f - a);
        for (float s : {inner, std::nextafter(inner, 0.0f), std::nextafter(inner, 10.0f)}) {
            const float v = sh::eclipse_visible_exact(a, s, kU);
            ASSERT_TRUE(std::isfinite(v));
            EXPECT_NEAR(v, visible_fraction_reference(a, s, kU), 1e-6) << "a=" << a << " s=" << s;
        }
    }
}

TEST(EclipseStability, CasterBehindTheReceiverOrBeyondTheSunCastsNothing) {
    const float au = 1.496e11f, sun_r = 6.957e8f, moon_r = 1.7374e6f;
    const sh::vec3 to_sun(0.0f, 0.0f, au);
    for (const sh::vec3& to_caster : {sh::vec3(0.0f, 0.0f, -3.844e8f), sh::vec3(1e3f, 0.0f, -3.844e8f),
                                      sh::vec3(3.844e8f, 0.0f, 0.0f), sh::vec3(0.0f, 0.0f, 2.0f * au)}) {
        const sh::EclipseDiscs d = sh::eclipse_discs(to_sun, sun_r, to_caster, moon_r);
        EXPECT_GE(d.separation, 1.0f + d.ratio);
        EXPECT_EQ(sh::eclipse_visible_exact(d.ratio, d.separation, kU), 1.0f);
        EXPECT_EQ(sh::eclipse_visible_fast(d.ratio, d.separation, 4.0f), 1.0f);
        EXPECT_EQ(lut_visible(d.ratio, d.separation), 1.0f);
        EXPECT_EQ(sh::eclipse_region(d.ratio, d.separation), 3);
    }
}

TEST(EclipseStability, CasterLargerThanTheSun) {
    for (float a : {3.7f, 100.0f}) expect_monotone_and_accurate(a, closing_separations(a), 1e-6, 2 * kUlp1);
    EXPECT_EQ(sh::eclipse_visible_exact(3.7f, 2.6f, kU), 0.0f);
    EXPECT_EQ(sh::eclipse_visible_exact(100.0f, 98.5f, kU), 0.0f);
    // Earth seen from the Moon (a lunar eclipse from the Moon's side): a ~ 3.7.
    const glm::dvec3 sun(1.496e11, 0.0, 0.0), earth(0.0), moon(-3.844e8, 0.0, 0.0);
    const sh::EclipseDiscs d = sh::eclipse_discs(sh::vec3(sun - moon), 6.957e8f, sh::vec3(earth - moon), 6.371e6f);
    EXPECT_NEAR(d.ratio, 3.6, 0.15);
    EXPECT_EQ(d.separation, 0.0f);
    EXPECT_EQ(sh::eclipse_visible_exact(d.ratio, d.separation, kU), 0.0f);
}

TEST(EclipseStability, ReceiverExactlyOnTheShadowAxis) {
    // Collinear vectors along an axis: the unit vectors are equal, s = 0 exactly.
    const sh::EclipseDiscs d =
        sh::eclipse_discs(sh::vec3(0.0f, 1.496e11f, 0.0f), 6.957e8f, sh::vec3(0.0f, 3.7e8f, 0.0f), 1.7374e6f);
    EXPECT_EQ(d.separation, 0.0f);
    EXPECT_NEAR(sh::eclipse_visible_exact(d.ratio, d.separation, kU), visible_fraction_reference(d.ratio, 0.0, kU),
                3e-7);
    // Collinear along a skew direction: normalisation rounds, s stays ~1e-5 and the result that of s = 0.
    const sh::vec3 dir = sh::normalize(sh::vec3(0.3f, -0.5f, 0.8f));
    for (float moon_distance : {3.6e8f, 3.7e8f, 3.844e8f, 4.0e8f}) {
        const sh::EclipseDiscs e = sh::eclipse_discs(dir * 1.496e11f, 6.957e8f, dir * moon_distance, 1.7374e6f);
        EXPECT_LT(e.separation, 1e-4f);
        const double v0 = visible_fraction_reference(e.ratio, 0.0, kU);
        EXPECT_NEAR(sh::eclipse_visible_exact(e.ratio, e.separation, kU), v0, 1e-6) << moon_distance;
        EXPECT_NEAR(lut_visible(e.ratio, e.separation), v0, 2.5e-3) << moon_distance;
    }
}

TEST(EclipseStability, OneAuFromTheOriginFloatAgainstDouble) {
    // Sun, Moon and a receiver on the Earth, all ~1.5e11 m from the origin (an equilateral
    // origin-Sun-Earth triangle), the Moon placed so the receiver sees separation s_target.
    const double au = 1.495978707e11, sun_r = 6.957e8, moon_r = 1.7374e6, moon_d = 3.844e8;
    const glm::dvec3 sun = au * glm::dvec3(std::cos(0.3), std::sin(0.3), 0.01);
    const glm::dvec3 receiver = au * glm::dvec3(std::cos(0.3 + kPi / 3), std::sin(0.3 + kPi / 3), -0.02);
    const glm::dvec3 to_sun = glm::normalize(sun - receiver);
    const glm::dvec3 side = glm::normalize(glm::cross(to_sun, glm::dvec3(0.2, 0.3, 1.0)));
    const double alpha_sun = std::asin(sun_r / glm::length(sun - receiver));
    const double a_expected = std::asin(moon_r / moon_d) / alpha_sun;
    double worst_cupola = 0.0, worst_naive_penumbra = 0.0;
    for (double s_target : {0.0, 0.01, 0.5 * std::fabs(1.0 - a_expected), 0.5, 1.0, 1.5, 1.0 + a_expected - 0.05,
                            1.0 + a_expected - 0.005}) {
        const double angle = s_target * alpha_sun;
        const glm::dvec3 moon = receiver + moon_d * (std::cos(angle) * to_sun + std::sin(angle) * side);
        // All double.
        const DiscsD dd = discs_double(sun - receiver, sun_r, moon - receiver, moon_r);
        const double v_double = visible_fraction_reference(dd.ratio, dd.separation, kU);
        // Cupola: differences in double relative to the receiver, then float.
        const sh::EclipseDiscs dc = sh::eclipse_discs(sh::vec3(sun - receiver), static_cast<float>(sun_r),
                                                      sh::vec3(moon - receiver), static_cast<float>(moon_r));
        const double v_cupola = sh::eclipse_visible_exact(dc.ratio, dc.separation, kU);
        // Naive: positions rounded to float first, differences in float.
        const sh::vec3 sun_f(sun), moon_f(moon), receiver_f(receiver);
        const sh::EclipseDiscs dn = sh::eclipse_discs(sun_f - receiver_f, static_cast<float>(sun_r),
                                                      moon_f - receiver_f, static_cast<float>(moon_r));
        const double v_naive = sh::eclipse_visible_exact(dn.ratio, dn.separation, kU);
        std::printf("s=%.4f: double %.9f  cupola %.9f (%.2g, s off by %.2g)  naive %.9f (%.2g, s off by %.2g)\n",
                    dd.separation, v_double, v_cupola, v_cupola - v_double, dc.separation - dd.separation, v_naive,
                    v_naive - v_double, dn.separation - dd.separation);
        EXPECT_NEAR(dd.separation, s_target, 1e-9);
        EXPECT_NEAR(v_cupola, v_double, 1e-5) << "s=" << s_target;
        worst_cupola = std::max(worst_cupola, std::fabs(v_cupola - v_double));
        if (s_target > std::fabs(1.0 - a_expected) && s_target < 1.0 + a_expected)
            worst_naive_penumbra = std::max(worst_naive_penumbra, std::fabs(v_naive - v_double));
    }
    RecordProperty("cupola_max_error", sci(worst_cupola));
    RecordProperty("naive_max_error_penumbra", sci(worst_naive_penumbra));
    // Rounding 1.5e11 m to float moves each body by up to 8 km: 2e-5 rad at the Moon's distance,
    // ~5e-3 of the Sun's radius, so the naive path is off by ~1e-3 in the penumbra.
    EXPECT_GT(worst_naive_penumbra, 1e-3);
    EXPECT_GT(worst_naive_penumbra, 100.0 * worst_cupola);
}

// ---------------------------------------------------------------------------------------------
// The GPU runs the same text: compare it with the C++ build.

TEST(EclipseShadowGpu, SharedFunctionsAgreeBetweenGpuAndCpu) {
    static EglContext* ctx = [] {
        unsetenv("DISPLAY");
        unsetenv("WAYLAND_DISPLAY");
        return new EglContext(-1);
    }();
    (void)ctx;
    // One (a, s) per pixel: log2 a across [-7, 7] (and a = 1 +- small), s across [0, 1.1 (1 + a)],
    // plus the contacts.
    const int n = 64;
    std::vector<glm::vec4> params(static_cast<size_t>(n) * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            float a = std::exp2(-7.0f + 14.0f * x / (n - 1));
            if (x % 8 == 3) a = 1.0f + (x - n / 2) * 1e-3f;
            float s = 1.1f * (1.0f + a) * y / (n - 1);
            if (y == n - 1) s = 1.0f + a;
            if (y == n - 2) s = std::fabs(1.0f - a);
            if (y == n - 3) s = a;
            params[static_cast<size_t>(y) * n + x] = glm::vec4(a, s, 0.0f, 1.0f);
        }
    const GlTexture param_tex(n, n, params.data(), GL_NEAREST);
    const sh::Texture2DData& lut = default_lut();
    const GlTexture lut_tex(lut.width, lut.height, lut.texels.data(), GL_LINEAR);
    GlFramebuffer fb(n, n);
    GlProgram prog("tests/fullscreen.vert", "tests/eclipse_eval.frag");
    GlEmptyVertexArray vao;
    fb.bind();
    prog.use();
    param_tex.bind(0);
    lut_tex.bind(1);
    prog.set("u_params", 0);
    prog.set("u_lut", 1);
    prog.set("u_lut_size", default_lut_size());
    prog.set("u_limb_u", kU);
    prog.set("u_order", 4.0f);
    prog.set("u_mode", -1);
    vao.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    const Image img = fb.read();
    ErrorStats diff[3], gpu_exact_vs_reference;
    for (int yi = 0; yi < n; ++yi)
        for (int x = 0; x < n; ++x) {
            const int y = n - 1 - yi;  // image row 0 is the top
            const glm::vec4 p = params[static_cast<size_t>(y) * n + x];
            const float* g = img.pixel(x, yi);
            const float cpu[3] = {sh::eclipse_visible_exact(p.x, p.y, kU), sh::eclipse_visible_fast(p.x, p.y, 4.0f),
                                  lut_visible(p.x, p.y)};
            for (int m = 0; m < 3; ++m) {
                ASSERT_TRUE(std::isfinite(g[m])) << m << " a=" << p.x << " s=" << p.y;
                diff[m].add(std::fabs(g[m] - cpu[m]), p.x, p.y);
            }
            ASSERT_EQ(static_cast<int>(g[3]), sh::eclipse_region(p.x, p.y)) << "a=" << p.x << " s=" << p.y;
            gpu_exact_vs_reference.add(std::fabs(g[0] - visible_fraction_reference(p.x, p.y, kU)), p.x, p.y);
        }
    RecordProperty("gpu_exact_vs_reference_max", sci(gpu_exact_vs_reference.max));
    std::printf("GPU exact vs reference: max %.3g (%s), mean %.3g\n", gpu_exact_vs_reference.max,
                gpu_exact_vs_reference.where().c_str(), gpu_exact_vs_reference.mean());
    EXPECT_LT(gpu_exact_vs_reference.max, 2e-6) << gpu_exact_vs_reference.where();
    const char* names[3] = {"exact", "fast", "lut"};
    for (int m = 0; m < 3; ++m) {
        RecordProperty(std::string(names[m]) + "_max_gpu_cpu", sci(diff[m].max));
        std::printf("GPU vs CPU %s: max %.3g (%s), mean %.3g\n", names[m], diff[m].max, diff[m].where().c_str(),
                    diff[m].mean());
        EXPECT_LT(diff[m].max, 1e-5) << names[m] << " " << diff[m].where();
    }
}

// CPU tests of the sun-glare point-spread function of shaders/shared/glare_psf.glsl, compiled as
// C++ through common/shading/shared_shading.hpp (the GPU runs the same text). Reference integrals
// are done here in double, independently of the shared code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "shading/shared_shading.hpp"

namespace sh = cupola::shading;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

sh::GlareParams default_params() {
    sh::GlareParams p;
    p.strength = 1.0f;
    p.extent_rad = static_cast<float>(60.0 * kDeg);
    p.halo_radius_rad = static_cast<float>(3.5 * kDeg);
    p.halo_width_rad = static_cast<float>(0.35 * kDeg);
    p.halo_fraction = 0.15f;
    p.streak_count = 96.0f;
    p.streak_contrast = 0.6f;
    p.phase = 0.0f;
    return p;
}

// Spencer et al. 1995's photopic terms, written out here in double (theta in radians in, the
// formula's degrees inside), per sr.
double spencer_core(double theta) { return 0.384 * 2.61e6 * std::exp(-std::pow(theta / kDeg / 0.02, 2)); }
double spencer_flare(double theta) { return 0.478 * 20.91 / std::pow(theta / kDeg + 0.02, 3); }
double spencer_bloom(double theta) { return 0.138 * 72.37 / std::pow(theta / kDeg + 0.02, 2); }

// integral_0^tmax f(theta) 2 pi sin(theta) dtheta, midpoint rule in u = ln(theta + s), s = 0.02
// deg (the PSF's own scale): even steps across five decades of angle.
template <class F>
double integrate_sphere(F f, double tmax, int n = 200000) {
    const double s = 0.02 * kDeg;
    const double u0 = std::log(s), u1 = std::log(tmax + s);
    const double h = (u1 - u0) / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double u = u0 + (i + 0.5) * h;
        const double t = std::exp(u) - s;
        sum += f(t) * 2.0 * kPi * std::sin(t) * (t + s) * h;
    }
    return sum;
}

double fade(double theta, double extent) {
    if (theta >= extent) return 0.0;
    const double e0 = 0.85 * extent;
    const double x = std::clamp((theta - e0) / (extent - e0), 0.0, 1.0);
    return 1.0 - x * x * (3.0 - 2.0 * x);
}

// Mean of glare_streaks over phi in [-pi, pi), midpoint rule with n samples.
double streak_mean(const sh::GlareParams& p, int n) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += sh::glare_streaks(p, static_cast<float>(-kPi + (i + 0.5) * 2.0 * kPi / n));
    return sum / n;
}

// integral of glare_psf over theta in [0, extent], phi in [-pi, pi), per channel.
glm::dvec3 psf_energy(const sh::GlareParams& p) {
    const int nt = 1500, np = 9600;  // 100 phi samples per streak cell, 20 across each ray
    const double s = 0.02 * kDeg;
    const double u0 = std::log(s), u1 = std::log(p.extent_rad + s);
    const double ht = (u1 - u0) / nt, hp = 2.0 * kPi / np;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < nt; ++i) {
        const double t = std::exp(u0 + (i + 0.5) * ht) - s;
        const double w = std::sin(t) * (t + s) * ht * hp;
        glm::dvec3 ring(0.0);
        for (int j = 0; j < np; ++j)
            ring += glm::dvec3(sh::glare_psf(p, static_cast<float>(t), static_cast<float>(-kPi + (j + 0.5) * hp)));
        sum += ring * w;
    }
    return sum;
}

sh::vec3 to_float(const glm::dvec3& v) { return sh::vec3(v); }

bool finite(const sh::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

// 1. Units of Spencer's formula. Found (true element 2 pi sin(theta) dtheta):
//    0.478 f1 integrates to 0.478 x 0.9997 by 60 deg and 0.478 x 1.0000 by 180 deg (it converges);
//    0.138 f2 integrates to 0.138 x 0.99994 over the hemisphere (90 deg), 0.138 x 0.981 to 74 deg
//    (74 deg is where the small-angle form reaches 1), 0.138 x 1.033 to 180 deg (it diverges
//    logarithmically); the core 0.384 f0 to 0.384 x 0.9991. So theta is in degrees and the value is
//    per steradian: a per-deg^2 reading would be off by 3282.8. Tolerance 0.1 % (the numbers above
//    are good to 1e-5; the formula's own coefficients have 3-4 digits).
TEST(GlarePsf, SpencerTermsIntegrateToTheirWeights) {
    EXPECT_NEAR(integrate_sphere(spencer_flare, kPi) / 0.478, 1.0, 1e-3);
    EXPECT_NEAR(integrate_sphere(spencer_bloom, 0.5 * kPi) / 0.138, 1.0, 1e-3);
    EXPECT_NEAR(integrate_sphere(spencer_core, 1.0 * kDeg) / 0.384, 1.0, 1e-3);
    // The divergence of the bloom term: beyond the hemisphere it grows past its weight.
    EXPECT_GT(integrate_sphere(spencer_bloom, kPi) / 0.138, 1.02);
    // The shared functions are these terms (float, so 1e-5 relative).
    for (double deg : {0.0, 1e-4, 0.01, 0.1, 1.0, 3.5, 10.0, 45.0, 89.0}) {
        const float t = static_cast<float>(deg * kDeg);
        EXPECT_NEAR(sh::glare_flare(t) / spencer_flare(t), 1.0, 1e-5) << deg << " deg";
        EXPECT_NEAR(sh::glare_bloom(t) / spencer_bloom(t), 1.0, 1e-5) << deg << " deg";
    }
    // And they integrate to the same weights.
    auto flare = [](double t) { return static_cast<double>(sh::glare_flare(static_cast<float>(t))); };
    auto bloom = [](double t) { return static_cast<double>(sh::glare_bloom(static_cast<float>(t))); };
    EXPECT_NEAR(integrate_sphere(flare, kPi) / 0.478, 1.0, 1e-3);
    EXPECT_NEAR(integrate_sphere(bloom, 0.5 * kPi) / 0.138, 1.0, 1e-3);
}

// 2. The halo rings are normalised over the sphere per channel, red outside blue.
TEST(GlarePsf, HaloRingsIntegrateToOneRedOutside) {
    struct Ring {
        double radius_deg, width_deg;
    };
    // The default, a ring at the pole (a Gaussian spot), one barely off it, broad and wide ones.
    for (Ring r :
         {Ring{3.5, 0.35}, Ring{0.0, 0.35}, Ring{0.35, 0.35}, Ring{1.0, 0.6}, Ring{17.0, 5.7}, Ring{57.0, 3.0}}) {
        sh::GlareParams p = default_params();
        p.halo_radius_rad = static_cast<float>(r.radius_deg * kDeg);
        p.halo_width_rad = static_cast<float>(r.width_deg * kDeg);
        for (int c = 0; c < 3; ++c) {
            auto ring = [&](double t) { return static_cast<double>(sh::glare_halo(p, static_cast<float>(t))[c]); };
            EXPECT_NEAR(integrate_sphere(ring, kPi), 1.0, 1e-2)
                << "radius " << r.radius_deg << " deg, width " << r.width_deg << " deg, channel " << c;
        }
    }
    // Peaks: sample finely, red (x) at the largest angle, blue (z) at the smallest.
    const sh::GlareParams p = default_params();
    glm::dvec3 best(0.0), at(0.0);
    for (int i = 0; i < 20000; ++i) {
        const double t = i * 1e-3 * kDeg;  // 0 .. 20 deg
        const sh::vec3 h = sh::glare_halo(p, static_cast<float>(t));
        for (int c = 0; c < 3; ++c)
            if (h[c] > best[c]) best[c] = h[c], at[c] = t;
    }
    EXPECT_GT(at.x, at.y);
    EXPECT_GT(at.y, at.z);
    EXPECT_NEAR(at.x / kDeg, 3.5 * 610.0 / 550.0, 2e-3);
    EXPECT_NEAR(at.y / kDeg, 3.5, 2e-3);
    EXPECT_NEAR(at.z / kDeg, 3.5 * 465.0 / 550.0, 2e-3);
}

// 3. Streaks: mean 1 over phi at every phase, continuous across +-pi, exactly 1 without contrast.
TEST(GlarePsf, StreaksKeepTheMeanAtEveryPhase) {
    sh::GlareParams p = default_params();
    const int n = 96 * 2000;
    const double mean0 = streak_mean(p, n);
    EXPECT_NEAR(mean0, 1.0, 1e-3);
    double lo = 1e9, hi = -1e9;
    for (int k = 0; k < 20; ++k) {
        p.phase = static_cast<float>(100.0 * k / 19.0);
        const double m = streak_mean(p, n);
        EXPECT_NEAR(m, mean0, 1e-3) << "phase " << p.phase;
        EXPECT_NEAR(m, 1.0, 1e-3) << "phase " << p.phase;
        lo = std::min(lo, m), hi = std::max(hi, m);
    }
    EXPECT_LT(hi - lo, 1e-3);
    // Other counts, odd ones rounded to even, and other contrasts.
    for (float count : {2.0f, 7.0f, 12.0f, 31.0f, 200.0f})
        for (float contrast : {0.3f, 1.0f}) {
            sh::GlareParams q = default_params();
            q.streak_count = count, q.streak_contrast = contrast, q.phase = 13.7f;
            EXPECT_NEAR(streak_mean(q, 400000), 1.0, 1e-3) << "count " << count << " contrast " << contrast;
        }
    // The rays really flicker: the pattern itself changes with phase (else the test above is empty).
    {
        sh::GlareParams a = default_params(), b = default_params();
        b.phase = 3.0f;
        double diff = 0.0;
        for (int i = 0; i < 10000; ++i) {
            const float phi = static_cast<float>(-kPi + (i + 0.5) * 2.0 * kPi / 10000);
            const float d = sh::glare_streaks(a, phi) - sh::glare_streaks(b, phi);
            diff = std::max(diff, static_cast<double>(std::fabs(d)));
        }
        EXPECT_GT(diff, 0.5);
    }
}

TEST(GlarePsf, StreaksAreContinuousAcrossPi) {
    for (float phase : {0.0f, 5.5f, 37.3f}) {
        sh::GlareParams p = default_params();
        p.phase = phase;
        const float pi = static_cast<float>(kPi);
        EXPECT_NEAR(sh::glare_streaks(p, pi), sh::glare_streaks(p, -pi), 1e-4);
        // Just either side: the steepest ray flank is c / 0.05 / (0.1 cell) ~ 1833 per radian.
        const float d = 1e-5f;
        EXPECT_NEAR(sh::glare_streaks(p, pi - d), sh::glare_streaks(p, -pi + d), 2.0 * 1833.0 * 2.0 * d);
        // Everywhere, including phi = 0 (where fract wraps): no jump larger than the steepest slope
        // allows between neighbouring samples.
        const int n = 2000000;
        const double step = 2.0 * kPi / n;
        float prev = sh::glare_streaks(p, static_cast<float>(-kPi));
        double worst = 0.0;
        for (int i = 1; i <= n; ++i) {
            const float cur = sh::glare_streaks(p, static_cast<float>(-kPi + i * step));
            worst = std::max(worst, static_cast<double>(std::fabs(cur - prev)));
            prev = cur;
        }
        EXPECT_LT(worst, 2.0 * 1833.0 * step) << "phase " << phase;
    }
}

TEST(GlarePsf, StreaksWithoutContrastAreExactlyOne) {
    sh::GlareParams p = default_params();
    p.streak_contrast = 0.0f;
    for (float phase : {0.0f, 37.3f})
        for (int i = 0; i < 10000; ++i) {
            p.phase = phase;
            EXPECT_EQ(sh::glare_streaks(p, static_cast<float>(-kPi + i * 2.0 * kPi / 10000)), 1.0f);
        }
}

// 4. Energy: the whole PSF holds the scattered terms' energy (rays and ring only move it), and
// the animation does not change it.
TEST(GlarePsf, EnergyIsTheScatteredTermsAndIndependentOfPhase) {
    sh::GlareParams p = default_params();
    p.strength = 1.7f;
    const double extent = p.extent_rad;
    const double expected =
        p.strength *
        integrate_sphere([&](double t) { return (spencer_flare(t) + spencer_bloom(t)) * fade(t, extent); }, extent);
    // About 0.478 + 0.95 x 0.138 per unit strength, as the header says.
    EXPECT_NEAR(expected / p.strength, 0.478 + 0.95 * 0.138, 0.01);
    const glm::dvec3 e0 = psf_energy(p);
    p.phase = 37.3f;
    const glm::dvec3 e1 = psf_energy(p);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(e0[c] / expected, 1.0, 1e-2) << "channel " << c;
        EXPECT_NEAR(e1[c] / e0[c], 1.0, 1e-3) << "channel " << c;
    }
}

// 5. Direction only: a common rotation of everything changes nothing; nothing beyond the extent;
// finite and positive at the centre.
TEST(GlarePsf, RadianceDependsOnTheDirectionAlone) {
    const sh::GlareParams p = default_params();
    const glm::dvec3 center = glm::normalize(glm::dvec3(0.3, -0.5, 0.81));
    const glm::dvec3 e1 = glm::normalize(glm::cross(center, glm::dvec3(0.0, 0.0, 1.0)));
    const glm::dvec3 e2 = glm::cross(center, e1);
    const sh::vec3 irr(1.0f, 0.9f, 0.8f);
    auto radiance = [&](const sh::GlareParams& q, const glm::dmat3& r, const glm::dvec3& v) {
        return sh::glare_radiance(q, to_float(r * v), to_float(r * center), to_float(r * e1), to_float(r * e2), irr);
    };
    // Directions at theta in [0.1, 0.9 extent] rad (float rounding of a unit vector moves theta by
    // ~1e-7 rad, 1e-5 relative needs theta >~ 0.05), phi spread around.
    std::vector<glm::dvec3> dirs;
    std::vector<double> phis;
    for (int i = 0; i < 40; ++i) {
        const double t = 0.1 + (0.9 * p.extent_rad - 0.1) * i / 39.0;
        const double phi = -kPi + 2.0 * kPi * std::fmod(0.618034 * i + 0.1, 1.0);
        dirs.push_back(std::cos(t) * center + std::sin(t) * (std::cos(phi) * e1 + std::sin(phi) * e2));
        phis.push_back(phi);
    }
    const glm::dmat3 id(1.0);
    const glm::dmat3 rots[] = {glm::dmat3(glm::rotate(glm::dmat4(1.0), 1.1, glm::dvec3(0.2, 0.9, -0.3))),
                               glm::dmat3(glm::rotate(glm::dmat4(1.0), 2.7, glm::dvec3(-1.0, 0.1, 0.4))),
                               glm::dmat3(glm::rotate(glm::dmat4(1.0), -0.4, glm::dvec3(0.0, 0.0, 1.0)))};
    sh::GlareParams smooth = p;  // no rays: the radial part is checked at 1e-5 everywhere
    smooth.streak_contrast = 0.0f;
    int gaps = 0;
    for (const glm::dmat3& r : rots)
        for (size_t i = 0; i < dirs.size(); ++i) {
            const sh::vec3 a = radiance(smooth, id, dirs[i]), b = radiance(smooth, r, dirs[i]);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c] / a[c], 1.0, 1e-5) << "dir " << i << " channel " << c;
            // With rays: 1e-5 where the streak pattern is flat (between rays); on a ray flank
            // (up to ~1800 per radian) the float rounding of phi (~1e-6 rad here) allows 1e-3.
            const float phi = static_cast<float>(phis[i]);
            const bool flat = sh::glare_streaks(p, phi - 1e-3f) == sh::glare_streaks(p, phi + 1e-3f) &&
                              sh::glare_streaks(p, phi) == sh::glare_streaks(p, phi + 1e-3f);
            const sh::vec3 ar = radiance(p, id, dirs[i]), br = radiance(p, r, dirs[i]);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(br[c] / ar[c], 1.0, flat ? 1e-5 : 1e-3) << "dir " << i;
            gaps += flat;
        }
    EXPECT_GT(gaps, 10);  // the strict check did run with rays on
    // Rotation near the halo and the core, where float theta is coarser (relative error ~1e-7 / theta): 2e-3.
    for (double t : {3e-4, 1e-3, 0.01, 0.055, 0.061, 0.068}) {
        const glm::dvec3 v = std::cos(t) * center + std::sin(t) * (std::cos(0.3) * e1 + std::sin(0.3) * e2);
        for (const glm::dmat3& r : rots) {
            const sh::vec3 a = radiance(smooth, id, v), b = radiance(smooth, r, v);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c] / a[c], 1.0, 2e-3) << "theta " << t << " channel " << c;
        }
    }
    // Zero from the extent on.
    for (double t : {static_cast<double>(p.extent_rad) + 1e-4, 1.2, 2.0, 3.1}) {
        const glm::dvec3 v = std::cos(t) * center + std::sin(t) * e1;
        EXPECT_EQ(radiance(p, id, v), sh::vec3(0.0f)) << "theta " << t;
    }
    // At the centre: finite and positive.
    const sh::vec3 c0 = sh::glare_radiance(p, to_float(center), to_float(center), to_float(e1), to_float(e2), irr);
    EXPECT_TRUE(finite(c0));
    EXPECT_GT(c0.x, 0.0f);
    EXPECT_GT(c0.y, 0.0f);
    EXPECT_GT(c0.z, 0.0f);
}

// 6. Flare and bloom fall strictly with angle.
TEST(GlarePsf, FlareAndBloomDecreaseStrictly) {
    float prev_f = sh::glare_flare(0.0f), prev_b = sh::glare_bloom(0.0f);
    for (int i = 0; i <= 600; ++i) {
        const float t = static_cast<float>(1e-6 * std::pow(kPi / 1e-6, i / 600.0));  // 1e-6 .. pi
        const float f = sh::glare_flare(t), b = sh::glare_bloom(t);
        EXPECT_LT(f, prev_f) << "theta " << t;
        EXPECT_LT(b, prev_b) << "theta " << t;
        prev_f = f, prev_b = b;
    }
}

// 7. Float safety at the centre and at the edge.
TEST(GlarePsf, FiniteAtTinyAnglesAndAtTheExtent) {
    sh::GlareParams p = default_params();
    for (float phase : {0.0f, 37.3f, 1000.0f}) {
        p.phase = phase;
        for (float phi : {0.0f, 1.0f, -3.14159265f, 3.14159265f}) {
            const sh::vec3 a = sh::glare_psf(p, 1e-7f, phi);
            EXPECT_TRUE(finite(a));
            EXPECT_GT(a.y, 0.0f);
            EXPECT_LT(a.y, 2.0f * (sh::glare_bloom(0.0f) + sh::glare_flare(0.0f) * 12.4f));
            const sh::vec3 e = sh::glare_psf(p, p.extent_rad, phi);
            EXPECT_TRUE(finite(e));
            EXPECT_EQ(e, sh::vec3(0.0f));
            const sh::vec3 in = sh::glare_psf(p, std::nextafter(p.extent_rad, 0.0f), phi);
            EXPECT_TRUE(finite(in));
            EXPECT_GE(in.y, 0.0f);
            EXPECT_LT(in.y, 1e-6f);  // the fade reaches 0 continuously
        }
    }
    EXPECT_TRUE(std::isfinite(sh::glare_flare(1e-7f)));
    EXPECT_TRUE(std::isfinite(sh::glare_bloom(1e-7f)));
    EXPECT_TRUE(finite(sh::glare_halo(p, 1e-7f)));
    // A zero-width, zero-radius halo does not divide by zero.
    p.halo_width_rad = 0.0f;
    p.halo_radius_rad = 0.0f;
    EXPECT_TRUE(finite(sh::glare_psf(p, 1e-7f, 0.0f)));
    EXPECT_TRUE(finite(sh::glare_psf(p, 0.0f, 0.0f)));
}

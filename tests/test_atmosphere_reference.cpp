// Tests of the CPU atmosphere reference (common/atmosphere/): geometry, closed-form toy
// atmospheres, phase-function normalisation, physical sanity, numerical hard cases and the
// statistics of the Monte Carlo multiple scattering.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_geometry.hpp"
#include "atmosphere/atmosphere_parameters.hpp"
#include "atmosphere/reference_integrator.hpp"

namespace at = cupola::atmosphere;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = 180.0 / kPi;

at::ReferenceSettings single_only() {
    at::ReferenceSettings s;
    s.scattering_orders = 1;
    s.ms_paths = 0;
    return s;
}

// An Earth-sized toy with Rayleigh only (no Mie, no ozone), optionally of uniform density.
at::AtmosphereParameters toy(double scale_height) {
    at::AtmosphereParameters p = at::AtmosphereParameters::earth();
    p.rayleigh_scale_height = scale_height;
    p.mie_extinction_at_550nm = 0.0;
    p.ozone_column_dobson = 0.0;
    return p;
}

bool all_finite_nonnegative(const std::vector<double>& v) {
    for (double x : v)
        if (!std::isfinite(x) || x < 0.0) return false;
    return true;
}

double wavelength_value(const at::ReferenceIntegrator& ri, const std::vector<double>& v, double lambda) {
    const auto& w = ri.wavelengths();
    for (std::size_t i = 0; i < w.size(); ++i)
        if (std::abs(w[i] - lambda) < 1e-9) return v[i];
    ADD_FAILURE() << "no wavelength " << lambda;
    return 0.0;
}

}  // namespace

// ---------------------------------------------------------------- parameters

TEST(AtmosphereParameters, EarthMatchesPublishedRgbCoefficients) {
    const auto p = at::AtmosphereParameters::earth();
    // Bruneton/Hillaire Rayleigh at 680/550/440 nm: (5.802, 13.558, 33.1)e-6 m^-1.
    EXPECT_NEAR(p.rayleigh_scattering(680.0), 5.802e-6, 0.002e-6);
    EXPECT_NEAR(p.rayleigh_scattering(550.0), 13.558e-6, 0.005e-6);
    EXPECT_NEAR(p.rayleigh_scattering(440.0), 33.1e-6, 0.05e-6);
    EXPECT_NEAR(p.mie_scattering(550.0), 3.996e-6, 1e-12);
    EXPECT_NEAR(p.mie_extinction(550.0), 4.44e-6, 1e-12);
    // Hillaire ozone absorption (0.65, 1.881, 0.085)e-6 m^-1 at the tent peak.
    EXPECT_NEAR(p.ozone_absorption(680.0), 6.5e-7, 1e-12);
    EXPECT_NEAR(p.ozone_absorption(550.0), 1.881e-6, 1e-12);
    EXPECT_NEAR(p.ozone_absorption(440.0), 8.5e-8, 1e-13);
    // Black-body Sun at 1 AU: ~1.8-2.0 W m^-2 nm^-1 in the visible, total ~1361 W m^-2.
    EXPECT_GT(p.solar_irradiance(500.0), 1.6);
    EXPECT_LT(p.solar_irradiance(500.0), 2.2);
    double total = 0.0;
    for (double l = 100.0; l < 20000.0; l += 0.5)
        total += at::blackbody_irradiance(l + 0.25, 5772.0, 6.957e8, 1.495978707e11) * 0.5;
    EXPECT_NEAR(total, 1361.0, 5.0);
}

TEST(AtmosphereParameters, HashIsStableAndSensitive) {
    const auto a = at::AtmosphereParameters::earth();
    auto b = at::AtmosphereParameters::earth();
    EXPECT_EQ(a.hash(), b.hash());
    EXPECT_EQ(a.hash_hex().size(), 64u);
    b.name = "renamed";
    EXPECT_EQ(a.hash(), b.hash());  // the label is not physics
    b.mie_g = 0.8000000001;
    EXPECT_NE(a.hash(), b.hash());
    auto c = at::AtmosphereParameters::earth();
    c.ground_albedo.anchors[0].second = 0.1000001;
    EXPECT_NE(a.hash(), c.hash());
    EXPECT_NE(a.hash(), at::AtmosphereParameters::mars().hash());
}

// ---------------------------------------------------------------- geometry

TEST(AtmosphereGeometry, HorizonDecisionAtEpsilon) {
    const double R = 6360000.0, top = 6420000.0;
    for (double alt : {1.0, 10.0, 1000.0, 59999.0, 1.0e6}) {
        const double r = R + alt;
        const double muh = at::f64::ray_sphere_horizon_mu(r, R);
        EXPECT_NEAR(muh, -std::sqrt(1.0 - (R / r) * (R / r)), 1e-9);
        for (double eps : {1e-6, 1e-4, 4e-3}) {
            EXPECT_TRUE(at::f64::ray_hits_sphere(r, muh - eps, R)) << alt << " " << eps;
            EXPECT_FALSE(at::f64::ray_hits_sphere(r, muh + eps, R)) << alt << " " << eps;
            // The ground distance puts the end point on the ground sphere.
            const double mu = muh - eps;
            const double d = at::f64::ray_sphere_near_m(r, mu, R);
            EXPECT_GT(d, 0.0);
            const double r_end = std::sqrt(r * r + d * d + 2.0 * r * mu * d);
            EXPECT_NEAR(r_end, R, 1e-6 * R) << alt << " " << eps;
            if (r <= top) {
                const double dt = at::f64::ray_sphere_far_m(r, muh + eps, top);
                EXPECT_GT(dt, 0.0);
                EXPECT_NEAR(std::sqrt(r * r + dt * dt + 2.0 * r * (muh + eps) * dt), top, 1e-6 * top);
            }
        }
    }
    // At the ground itself every downward ray hits, every upward one does not.
    EXPECT_TRUE(at::f64::ray_hits_sphere(R, -1e-12, R));
    EXPECT_FALSE(at::f64::ray_hits_sphere(R, 1e-12, R));
    EXPECT_DOUBLE_EQ(at::f64::ray_sphere_near_m(R, -1.0, R), 0.0);
}

TEST(AtmosphereGeometry, CameraOutsideMovesToEntry) {
    const double R = 6360000.0, top = 6420000.0;
    const double r = R + 1.0e6;
    // Straight down: entry 1000 km - 60 km below.
    auto e = at::enter_atmosphere(r, -1.0, R, top);
    ASSERT_TRUE(e.intersects);
    EXPECT_NEAR(e.offset_m, 1.0e6 - 60000.0, 1e-6);
    EXPECT_DOUBLE_EQ(e.r_m, top);
    EXPECT_NEAR(e.mu, -1.0, 1e-12);
    // Looking up or beside the atmosphere: no entry, no NaN.
    EXPECT_FALSE(at::enter_atmosphere(r, 0.5, R, top).intersects);
    const double mu_miss = -std::sqrt(1.0 - (top / r) * (top / r)) + 1e-6;
    EXPECT_FALSE(at::enter_atmosphere(r, mu_miss, R, top).intersects);
    // Tangent to the top sphere: enters with mu = 0 at the tangent point.
    const double mu_tan = -std::sqrt(1.0 - (top / r) * (top / r)) - 1e-9;
    e = at::enter_atmosphere(r, mu_tan, R, top);
    ASSERT_TRUE(e.intersects);
    EXPECT_TRUE(std::isfinite(e.mu));
    EXPECT_NEAR(e.mu, 0.0, 1e-3);
    // Camera inside the ground is raised to the minimum altitude.
    e = at::enter_atmosphere(R - 5.0, 0.3, R, top);
    EXPECT_DOUBLE_EQ(e.r_m, R + at::kMinCameraAltitude);
}

// ---------------------------------------------------------------- closed-form toys

TEST(AtmosphereToy, VerticalOpticalDepthMatchesClosedForm) {
    const auto p = at::AtmosphereParameters::earth();
    const at::ReferenceIntegrator ri(p, single_only());
    const double htop = p.top_radius - p.bottom_radius;
    for (double h : {0.0, 500.0, 5000.0, 20000.0, 45000.0}) {
        const double r = p.bottom_radius + h;
        const glm::dvec3 d = ri.column_density(r, 1.0, p.top_radius - r);
        const double ray = p.rayleigh_scale_height *
                           (std::exp(-h / p.rayleigh_scale_height) - std::exp(-htop / p.rayleigh_scale_height));
        const double mie =
            p.mie_scale_height * (std::exp(-h / p.mie_scale_height) - std::exp(-htop / p.mie_scale_height));
        EXPECT_NEAR(d.x, ray, 1e-9 * ray) << h;
        EXPECT_NEAR(d.y, mie, 1e-9 * mie + 1e-12) << h;
    }
    // Ozone tent from the ground: exactly half of (top - bottom) of the tent.
    const glm::dvec3 d = ri.column_density(p.bottom_radius, 1.0, htop);
    EXPECT_NEAR(d.z, 15000.0, 1e-6);
    // Per-wavelength optical depth is the linear combination.
    const auto tau = ri.optical_depth(p.bottom_radius, 1.0, htop);
    EXPECT_NEAR(wavelength_value(ri, tau, 550.0),
                p.rayleigh_scattering(550.0) * d.x + p.mie_extinction(550.0) * d.y + p.ozone_absorption(550.0) * d.z,
                1e-12);
}

TEST(AtmosphereToy, HorizontalTransmittanceOfUniformShell) {
    const auto p = toy(std::numeric_limits<double>::infinity());
    const at::ReferenceIntegrator ri(p, single_only());
    for (double h : {1.0, 1000.0, 30000.0}) {
        const double r = p.bottom_radius + h;
        const auto t = ri.transmittance(r, 0.0);
        const double len = std::sqrt(p.top_radius * p.top_radius - r * r);
        for (std::size_t k = 0; k < t.size(); ++k) {
            const double expected = std::exp(-ri.rayleigh_scattering()[k] * len);
            EXPECT_NEAR(t[k], expected, 1e-12 + 1e-10 * expected) << h << " " << ri.wavelengths()[k];
        }
    }
}

TEST(AtmosphereToy, SlantOpticalDepthConvergesUnderRefinement) {
    // No closed form for a slant exponential path: the default panels must agree with a 20x finer
    // quadrature, including near-horizontal rays that pass their tangent point.
    const auto p = at::AtmosphereParameters::earth();
    at::ReferenceSettings fine = single_only();
    fine.panel_height_m = 12.5;
    const at::ReferenceIntegrator ri(p, single_only()), rf(p, fine);
    for (double h : {1.0, 2000.0, 30000.0}) {
        const double r = p.bottom_radius + h;
        const double muh = at::f64::ray_sphere_horizon_mu(r, p.bottom_radius);
        for (double mu : {1.0, 0.3, 0.05, 0.0, muh + 1e-6, muh - 1e-6, -0.5}) {
            const double len = at::f64::ray_shell_exit_m(r, mu, p.bottom_radius, p.top_radius);
            const glm::dvec3 a = ri.column_density(r, mu, len), b = rf.column_density(r, mu, len);
            EXPECT_NEAR(a.x, b.x, 1e-8 * b.x + 1e-9) << h << " " << mu;
            EXPECT_NEAR(a.y, b.y, 1e-7 * b.y + 1e-9) << h << " " << mu;
            EXPECT_NEAR(a.z, b.z, 1e-8 * b.z + 1e-9) << h << " " << mu;
        }
    }
}

// ---------------------------------------------------------------- phase functions

TEST(AtmospherePhase, IntegrateToOneOverTheSphere) {
    // integral of P(nu) 2 pi dnu over [-1, 1] by Simpson in s with nu = 1 - s^2 (s in [0, sqrt 2]),
    // which resolves the forward peak: dnu = -2 s ds.
    auto integrate = [](auto f) {
        const int n = 200000;  // even
        const double a = 0.0, b = std::sqrt(2.0), hstep = (b - a) / n;
        double sum = 0.0;
        for (int i = 0; i <= n; ++i) {
            const double s = a + i * hstep;
            const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
            sum += w * f(1.0 - s * s) * 2.0 * s;
        }
        return 2.0 * kPi * sum * hstep / 3.0;
    };
    EXPECT_NEAR(integrate([](double nu) { return at::rayleigh_phase(nu); }), 1.0, 1e-9);
    for (double g : {0.0, 0.5, 0.8, 0.9}) {
        EXPECT_NEAR(integrate([g](double nu) { return at::cornette_shanks_phase(g, nu); }), 1.0, 1e-7) << g;
        EXPECT_NEAR(integrate([g](double nu) { return at::henyey_greenstein_phase(g, nu); }), 1.0, 1e-7) << g;
    }
    // Cornette-Shanks with g = 0 is the Rayleigh phase function.
    EXPECT_NEAR(at::cornette_shanks_phase(0.0, 0.3), at::rayleigh_phase(0.3), 1e-15);
    // Without its (2 + g^2) factor the normalisation would be off: the factor matters.
    EXPECT_GT(
        std::abs(integrate([](double nu) { return at::cornette_shanks_phase(0.8, nu) * (2.0 + 0.64) / 2.0; }) - 1.0),
        0.1);
}

// ---------------------------------------------------------------- physical sanity

TEST(AtmosphereSanity, ZenithSkyIsBlueAndSunsetHorizonIsRed) {
    const at::ReferenceIntegrator ri(at::AtmosphereParameters::earth(), single_only());
    const auto noon = ri.sky({0.0, 0.0, 30.0, 0.0});
    std::cout << "[ zenith, sun 30 ] rgb " << noon.rgb.x << " " << noon.rgb.y << " " << noon.rgb.z << "  L "
              << noon.luminance << " cd/m^2 (single scattering)\n";
    EXPECT_GT(noon.rgb.z, noon.rgb.y);
    EXPECT_GT(noon.rgb.y, noon.rgb.x);
    EXPECT_GT(noon.rgb.x, 0.0);
    EXPECT_FALSE(noon.hits_ground);
    const auto sunset = ri.sky({0.0, 85.0, 88.0, 0.0});
    const double rb_noon = noon.rgb.x / noon.rgb.z, rb_sunset = sunset.rgb.x / sunset.rgb.z;
    std::cout << "[ horizon toward sun, sun 88 ] rgb " << sunset.rgb.x << " " << sunset.rgb.y << " " << sunset.rgb.z
              << "  r/b " << rb_sunset << " vs noon zenith " << rb_noon << "\n";
    EXPECT_GT(rb_sunset, 3.0 * rb_noon);
    EXPECT_GT(sunset.rgb.x, sunset.rgb.z);
}

TEST(AtmosphereSanity, NightSingleScatteringIsZero) {
    const at::ReferenceIntegrator ri(at::AtmosphereParameters::earth(), single_only());
    const double day = ri.sky({0.0, 0.0, 30.0, 0.0}).luminance;
    for (double vz : {0.0, 60.0, 89.0, 95.0, 150.0})
        for (double az : {0.0, 90.0, 180.0}) {
            const auto s = ri.sky({0.0, vz, 110.0, az});
            EXPECT_LE(s.luminance, 1e-9 * day) << vz << " " << az;
            EXPECT_TRUE(all_finite_nonnegative(s.spectrum));
        }
    // Twilight at altitude: sun 10 degrees below the horizon, still lit high up toward the Sun.
    const auto twilight = ri.sky({0.0, 80.0, 100.0, 0.0});
    EXPECT_GT(twilight.luminance, 0.0);
    EXPECT_LT(twilight.luminance, 0.05 * day);
}

TEST(AtmosphereSanity, TransmittanceIsMonotonicAndBlueIsDimmer) {
    const auto p = at::AtmosphereParameters::earth();
    const at::ReferenceIntegrator ri(p, single_only());
    const double r = p.bottom_radius + 100.0;
    const double muh = at::f64::ray_sphere_horizon_mu(r, p.bottom_radius);
    std::vector<double> prev;
    for (int i = 0; i <= 100; ++i) {
        const double mu = muh + 1e-6 + (1.0 - muh - 1e-6) * std::pow(i / 100.0, 2.0);
        const auto t = ri.transmittance(r, mu);
        for (std::size_t k = 0; k < t.size(); ++k) {
            EXPECT_GT(t[k], 0.0);
            EXPECT_LE(t[k], 1.0);
            if (!prev.empty()) {
                EXPECT_GE(t[k], prev[k]) << mu;
            }
        }
        prev = t;
    }
    // Vertical transmittance grows with altitude.
    std::vector<double> low = ri.transmittance(p.bottom_radius, 1.0);
    for (double h : {1000.0, 10000.0, 30000.0, 59000.0}) {
        const auto t = ri.transmittance(p.bottom_radius + h, 1.0);
        for (std::size_t k = 0; k < t.size(); ++k) EXPECT_GT(t[k], low[k]);
        low = t;
    }
    const auto horiz = ri.transmittance(r, 0.0);
    EXPECT_LT(wavelength_value(ri, horiz, 440.0), wavelength_value(ri, horiz, 680.0));
}

TEST(AtmosphereSanity, MultipleScatteringAddsAPositiveShare) {
    at::ReferenceSettings s;  // defaults: 4 orders
    s.ms_paths = 512;
    const at::ReferenceIntegrator ri(at::AtmosphereParameters::earth(), s);
    const auto t0 = std::chrono::steady_clock::now();
    const auto sky = ri.sky({0.0, 0.0, 30.0, 0.0});
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const double share = sky.multiple_luminance / sky.luminance;
    std::cout << "[ zenith, sun 30, 4 orders ] L " << sky.luminance << " cd/m^2, single " << sky.single_luminance
              << ", multiple " << sky.multiple_luminance << " +- " << sky.multiple_luminance_stderr << " (share "
              << share << "), rgb " << sky.rgb.x << " " << sky.rgb.y << " " << sky.rgb.z << ", " << ms << " ms for "
              << s.ms_paths << " paths\n";
    EXPECT_GT(sky.multiple_luminance, 4.0 * sky.multiple_luminance_stderr);
    EXPECT_GT(share, 0.05);
    EXPECT_LT(share, 0.40);
    for (std::size_t k = 0; k < sky.multiple_spectrum.size(); ++k) EXPECT_GE(sky.multiple_spectrum[k], 0.0);
    EXPECT_GT(sky.rgb.z, sky.rgb.y);
    EXPECT_GT(sky.rgb.y, sky.rgb.x);
}

// ---------------------------------------------------------------- hard cases

TEST(AtmosphereHardCases, NoNanOrInfAnywhere) {
    const auto p = at::AtmosphereParameters::earth();
    at::ReferenceSettings s;
    s.scattering_orders = 3;
    s.ms_paths = 4;
    const at::ReferenceIntegrator ri(p, s);
    const double htop = p.top_radius - p.bottom_radius;
    for (double alt : {0.0, -10.0, 1.0, htop, htop + 1.0, 1.0e6}) {
        const double r = std::max(p.bottom_radius + alt, p.bottom_radius + at::kMinCameraAltitude);
        const double muh = at::f64::ray_sphere_horizon_mu(r, p.bottom_radius);
        std::vector<double> zeniths = {0.0, 90.0, 180.0, 120.0};
        for (double eps : {1e-6, -1e-6}) zeniths.push_back(std::acos(muh + eps) * kDeg);
        for (double vz : zeniths)
            for (double sz : {30.0, 90.0, 100.0})
                for (double az : {0.0, 180.0}) {
                    const auto sky = ri.sky({alt, vz, sz, az});
                    ASSERT_TRUE(all_finite_nonnegative(sky.spectrum)) << alt << " " << vz << " " << sz << " " << az;
                    ASSERT_TRUE(all_finite_nonnegative(sky.multiple_stderr));
                    ASSERT_TRUE(std::isfinite(sky.luminance));
                    ASSERT_TRUE(std::isfinite(sky.rgb.x) && std::isfinite(sky.rgb.y) && std::isfinite(sky.rgb.z));
                }
    }
    // Transmittance at the exact boundaries and straight down from the ground (d_max == d_min).
    for (double mu : {-1.0, -1e-9, 0.0, 1e-9, 1.0}) {
        EXPECT_TRUE(all_finite_nonnegative(ri.transmittance(p.bottom_radius, mu)));
        EXPECT_TRUE(all_finite_nonnegative(ri.transmittance(p.top_radius, mu)));
    }
}

TEST(AtmosphereHardCases, LimbFromOrbitIsABrightRim) {
    const auto p = at::AtmosphereParameters::earth();
    const at::ReferenceIntegrator ri(p, single_only());
    const double alt = 1.0e6, r = p.bottom_radius + alt;
    auto grazing = [&](double h) {
        const double vz = 180.0 - std::asin((p.bottom_radius + h) / r) * kDeg;  // tangent at altitude h
        return ri.sky({alt, vz, 0.0, 0.0});
    };
    const auto l20 = grazing(20000.0), l50 = grazing(50000.0), l200 = grazing(200000.0);
    std::cout << "[ limb from 1000 km ] L(20 km) " << l20.luminance << "  L(50 km) " << l50.luminance << "  L(200 km) "
              << l200.luminance << "\n";
    EXPECT_TRUE(std::isfinite(l20.luminance));
    EXPECT_FALSE(l20.hits_ground);
    EXPECT_GT(l20.luminance, l200.luminance);
    EXPECT_GT(l20.luminance, 3.0 * l50.luminance);
    EXPECT_FALSE(l200.in_atmosphere);
    EXPECT_EQ(l200.luminance, 0.0);
    // The rim is brighter than the zenith sky seen from the ground (long path, Rayleigh-lit).
    EXPECT_GT(l20.luminance, ri.sky({0.0, 0.0, 30.0, 0.0}).luminance);
}

// ---------------------------------------------------------------- Monte Carlo statistics

TEST(AtmosphereMonteCarlo, DeterministicForAFixedSeed) {
    at::ReferenceSettings s;
    s.ms_paths = 48;
    s.seed = 7;
    const at::ReferenceIntegrator a(at::AtmosphereParameters::earth(), s), b(at::AtmosphereParameters::earth(), s);
    s.seed = 8;
    const at::ReferenceIntegrator c(at::AtmosphereParameters::earth(), s);
    const at::SkyQuery q{0.0, 60.0, 50.0, 90.0};
    const auto ra = a.sky(q), rb = b.sky(q), rc = c.sky(q);
    EXPECT_EQ(ra.multiple_spectrum, rb.multiple_spectrum);
    EXPECT_EQ(ra.multiple_luminance_stderr, rb.multiple_luminance_stderr);
    EXPECT_NE(ra.multiple_spectrum, rc.multiple_spectrum);
}

TEST(AtmosphereMonteCarlo, StandardErrorMatchesSeedScatter) {
    at::ReferenceSettings s;
    s.ms_paths = 64;
    const int seeds = 20;
    std::vector<double> means, errs;
    for (int i = 0; i < seeds; ++i) {
        s.seed = 1000 + i;
        const at::ReferenceIntegrator ri(at::AtmosphereParameters::earth(), s);
        const auto sky = ri.sky({0.0, 45.0, 40.0, 120.0});
        means.push_back(sky.multiple_luminance);
        errs.push_back(sky.multiple_luminance_stderr);
    }
    double m = 0.0, e = 0.0;
    for (int i = 0; i < seeds; ++i) {
        m += means[i] / seeds;
        e += errs[i] / seeds;
    }
    double var = 0.0;
    for (double x : means) var += (x - m) * (x - m) / (seeds - 1);
    const double ratio = std::sqrt(var) / e;
    std::cout << "[ MC ] mean " << m << " seed-to-seed sd " << std::sqrt(var) << " reported stderr " << e << " ratio "
              << ratio << "\n";
    EXPECT_GT(e, 0.0);
    EXPECT_GT(ratio, 0.5);
    EXPECT_LT(ratio, 1.8);
    // Two seeds agree within their combined error.
    EXPECT_LT(std::abs(means[0] - means[1]), 5.0 * std::hypot(errs[0], errs[1]));
}

TEST(AtmosphereMonteCarlo, FirstOrderEstimateMatchesQuadrature) {
    // Validation mode: the path tracer also estimates order 1 (sky and ground bounce); it must
    // agree with the deterministic quadrature within its own standard error.
    at::ReferenceSettings s;
    s.scattering_orders = 1;
    s.ms_first_order = 1;
    s.ms_paths = 4000;
    const at::ReferenceIntegrator ri(at::AtmosphereParameters::earth(), s);
    // Zenith; 1 m above the ground looking down (ground-dominated); sunset horizon; the globe
    // from 1000 km (entry point, ground and sky); an aircraft looking just below the horizon.
    for (const at::SkyQuery& q :
         {at::SkyQuery{0.0, 0.0, 30.0, 0.0}, at::SkyQuery{0.0, 120.0, 40.0, 0.0}, at::SkyQuery{0.0, 89.0, 88.0, 0.0},
          at::SkyQuery{1.0e6, 150.0, 30.0, 0.0}, at::SkyQuery{8000.0, 95.0, 60.0, 180.0}}) {
        const auto sky = ri.sky(q);
        const double det = sky.single_luminance + sky.ground_luminance;
        std::cout << "[ order 1 ] alt " << q.altitude_m << " vz " << q.view_zenith_deg << ": quadrature " << det
                  << "  MC " << sky.multiple_luminance << " +- " << sky.multiple_luminance_stderr << "\n";
        EXPECT_GT(det, 0.0);
        EXPECT_NEAR(sky.multiple_luminance, det, 4.5 * sky.multiple_luminance_stderr + 1e-6 * det);
        EXPECT_LT(sky.multiple_luminance_stderr, 0.02 * det);
        EXPECT_EQ(sky.spectrum, sky.multiple_spectrum);
    }
}

namespace {
void expect_agree(const at::SkyRadiance& a, const at::SkyRadiance& b, double sigmas, const std::string& what) {
    const double combined = std::hypot(a.multiple_luminance_stderr, b.multiple_luminance_stderr);
    EXPECT_GT(combined, 0.0) << what;
    EXPECT_NEAR(a.multiple_luminance, b.multiple_luminance, sigmas * combined) << what << " luminance";
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(a.multiple_rgb[k], b.multiple_rgb[k],
                    sigmas * std::hypot(a.multiple_rgb_stderr[k], b.multiple_rgb_stderr[k]))
            << what << " rgb " << k;
}

std::string describe(const at::SkyQuery& q) {
    return "alt " + std::to_string(q.altitude_m) + " vz " + std::to_string(q.view_zenith_deg) + " sz " +
           std::to_string(q.sun_zenith_deg) + " az " + std::to_string(q.relative_azimuth_deg);
}
}  // namespace

TEST(AtmosphereMonteCarlo, LineSampleAgreesWithTheCollisionEstimator) {
    // Unbiasedness of MsEstimator::kLitSegment (the line sample toward the sunlit air and the
    // twilight direction lobe): where the plain estimator (NEE at the collisions) is precise --
    // daylight, sunset, a camera in space -- both agree within their combined standard errors,
    // in luminance and in each colour channel, with different seeds.
    at::ReferenceSettings lit, plain;
    lit.ms_paths = 1024;
    plain.ms_paths = 2048;
    plain.ms_estimator = at::MsEstimator::kCollision;
    plain.seed = 2;
    const at::ReferenceIntegrator a(at::AtmosphereParameters::earth(), lit),
        b(at::AtmosphereParameters::earth(), plain);
    for (const at::SkyQuery& q : {at::SkyQuery{0.0, 0.0, 30.0, 0.0}, at::SkyQuery{0.0, 85.0, 65.0, 180.0},
                                  at::SkyQuery{0.0, 120.0, 40.0, 0.0}, at::SkyQuery{1.0e4, 60.0, 88.0, 0.0},
                                  at::SkyQuery{1.0e6, 140.0, 65.0, 30.0}, at::SkyQuery{4.0e5, 110.0, 30.0, 90.0}}) {
        const auto ra = a.sky(q), rb = b.sky(q);
        std::cout << "[ estimators ] " << describe(q) << ": line sample " << ra.multiple_luminance << " +- "
                  << ra.multiple_luminance_stderr << ", collisions " << rb.multiple_luminance << " +- "
                  << rb.multiple_luminance_stderr << "\n";
        expect_agree(ra, rb, 4.0, describe(q));
    }
}

TEST(AtmosphereMonteCarlo, LineSampleIsFarLessNoisyInTwilight) {
    // The reason for the line sample: with the Sun 5 degrees below the horizon the collisions fall
    // in the dense shadowed air, and few paths of the plain estimator collect any sunlight. With
    // the same paths, the line sample's standard error must be well below half the plain one,
    // and the two must still agree (the plain estimate given many more paths).
    at::ReferenceSettings lit, plain;
    lit.ms_paths = 512;
    plain.ms_paths = 512;
    plain.ms_estimator = at::MsEstimator::kCollision;
    const at::ReferenceIntegrator a(at::AtmosphereParameters::earth(), lit),
        b(at::AtmosphereParameters::earth(), plain);
    plain.ms_paths = 8192;
    const at::ReferenceIntegrator c(at::AtmosphereParameters::earth(), plain);
    for (const at::SkyQuery& q : {at::SkyQuery{0.0, 3.6, 95.0, 0.0}, at::SkyQuery{1.0e4, 60.0, 95.0, 180.0}}) {
        const auto ra = a.sky(q), rb = b.sky(q), rc = c.sky(q);
        std::cout << "[ twilight ] " << describe(q) << ": line sample " << ra.multiple_luminance << " +- "
                  << ra.multiple_luminance_stderr << ", collisions " << rb.multiple_luminance << " +- "
                  << rb.multiple_luminance_stderr << " (" << rc.multiple_luminance << " +- "
                  << rc.multiple_luminance_stderr << " with 8192 paths)\n";
        EXPECT_LT(ra.multiple_luminance_stderr, 0.5 * rb.multiple_luminance_stderr) << describe(q);
        expect_agree(ra, rc, 4.0, describe(q));
    }
}

TEST(AtmosphereMonteCarlo, AdaptiveCountStopsAtTheTargetOrTheCap) {
    at::ReferenceSettings s;
    s.ms_paths = 128;
    s.ms_max_paths = 2048;
    s.ms_target_noise = 0.01;
    const at::ReferenceIntegrator ri(at::AtmosphereParameters::earth(), s);
    for (const at::SkyQuery& q : {at::SkyQuery{0.0, 30.0, 30.0, 0.0}, at::SkyQuery{0.0, 30.0, 95.0, 0.0}}) {
        const auto sky = ri.sky(q);
        std::cout << "[ adaptive ] " << describe(q) << ": " << sky.ms_paths << " paths, noise "
                  << sky.multiple_luminance_stderr / sky.luminance << "\n";
        // Doubling from the first batch, up to the cap.
        EXPECT_TRUE(sky.ms_paths == 128 || sky.ms_paths == 256 || sky.ms_paths == 512 || sky.ms_paths == 1024 ||
                    sky.ms_paths == 2048)
            << sky.ms_paths;
        if (sky.ms_paths < 2048) {
            EXPECT_LE(sky.multiple_luminance_stderr, 0.01 * sky.luminance) << describe(q);
        }
        if (sky.ms_paths > 128) {  // the previous batch was not precise enough: it was not a free stop
            at::ReferenceSettings fixed = s;
            fixed.ms_max_paths = 0;
            fixed.ms_paths = sky.ms_paths / 2;
            const auto half = at::ReferenceIntegrator(at::AtmosphereParameters::earth(), fixed).sky(q);
            EXPECT_GT(half.multiple_luminance_stderr, 0.01 * half.luminance) << describe(q);
        }
        // The same as a fixed count of that many paths, bit for bit (path i uses stream i).
        at::ReferenceSettings fixed = s;
        fixed.ms_max_paths = 0;
        fixed.ms_paths = sky.ms_paths;
        const auto same = at::ReferenceIntegrator(at::AtmosphereParameters::earth(), fixed).sky(q);
        EXPECT_EQ(same.spectrum, sky.spectrum) << describe(q);
    }
    // The target floor: a sky far darker than it stops after the first batch.
    s.ms_target_floor = 1.0;
    const auto night = at::ReferenceIntegrator(at::AtmosphereParameters::earth(), s).sky({0.0, 30.0, 110.0, 0.0});
    EXPECT_LT(night.luminance, 1e-2);
    EXPECT_EQ(night.ms_paths, 128);
}

TEST(AtmosphereSanity, MarsPresetRuns) {
    at::ReferenceSettings s;
    s.ms_paths = 64;
    const at::ReferenceIntegrator ri(at::AtmosphereParameters::mars(), s);
    const auto noon = ri.sky({0.0, 30.0, 30.0, 180.0});
    std::cout << "[ mars ] rgb " << noon.rgb.x << " " << noon.rgb.y << " " << noon.rgb.z << " L " << noon.luminance
              << " (ms share " << noon.multiple_luminance / noon.luminance << ")\n";
    EXPECT_TRUE(all_finite_nonnegative(noon.spectrum));
    EXPECT_GT(noon.rgb.x, noon.rgb.z);  // dusty, reddish daytime sky
}

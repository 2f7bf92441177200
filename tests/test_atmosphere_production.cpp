// Tests of the production atmosphere model (shaders/shared/atmosphere_*.glsl compiled as C++,
// common/atmosphere/production_*.cpp): closed-form toy atmospheres, table-coordinate round trips,
// phase normalisation, the disk cache, numerical hard cases, and the error against the stored
// reference dataset (data/atmosphere/earth_reference.csv).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "atmosphere/atmosphere_geometry.hpp"
#include "atmosphere/production_accuracy.hpp"
#include "atmosphere/production_model.hpp"
#include "support/test_support.hpp"

namespace at = cupola::atmosphere;
namespace sh = cupola::shading;
using cupola::test::scratch_dir;
using cupola::test::source_path;

namespace {

at::TableCacheOptions no_cache() {
    at::TableCacheOptions c;
    c.enabled = false;
    return c;
}

// Earth-sized Rayleigh-only toy in the shader's terms (density profile switchable to uniform by
// a huge scale height: exp(-h / 1e30) == 1 in float).
sh::AtmosphereParams toy(float scale_height) {
    at::AtmosphereParameters p = at::AtmosphereParameters::earth();
    p.mie_extinction_at_550nm = 0.0;
    p.ozone_column_dobson = 0.0;
    sh::AtmosphereParams a = at::to_shader_params(p);
    a.rayleigh_scale_height_m = scale_height;
    a.mie_scale_height_m = 1.0f;
    return a;
}

bool finite_nonnegative(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0 && v.y >= 0 && v.z >= 0;
}

}  // namespace

// ---------------------------------------------------------------- closed forms on a toy planet

TEST(ProductionToy, VerticalOpticalDepthMatchesClosedForm) {
    const sh::AtmosphereParams a = toy(8000.0f);
    const double H = 8000.0, htop = a.top_radius_m - a.bottom_radius_m;
    for (double h : {0.0, 1000.0, 10000.0, 40000.0}) {
        const glm::vec3 t = sh::atm_compute_transmittance(a, static_cast<float>(a.bottom_radius_m + h), 1.0f, 400);
        for (int c = 0; c < 3; ++c) {
            const double tau = a.rayleigh_scattering_per_m[c] * H * (std::exp(-h / H) - std::exp(-htop / H));
            EXPECT_NEAR(-std::log(t[c]), tau, 2e-4 * tau) << h << " channel " << c;
        }
    }
}

TEST(ProductionToy, HorizontalTransmittanceOfUniformShell) {
    const sh::AtmosphereParams a = toy(1e30f);
    for (double h : {1.0, 2000.0, 30000.0}) {
        const double r = a.bottom_radius_m + h;
        const glm::vec3 t = sh::atm_compute_transmittance(a, static_cast<float>(r), 0.0f, 40);
        const double len = std::sqrt(double(a.top_radius_m) * a.top_radius_m - r * r);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], std::exp(-a.rayleigh_scattering_per_m[c] * len), 2e-5) << h;
    }
}

TEST(ProductionToy, RayGroundDecisionAtHorizonPlusMinusEpsilon) {
    const sh::AtmosphereParams a = toy(8000.0f);
    for (double h : {10.0, 1000.0, 50000.0}) {
        const double r = a.bottom_radius_m + h;
        const double muh = -std::sqrt(1.0 - std::pow(a.bottom_radius_m / r, 2));
        for (double eps : {1e-3, 4e-3}) {
            EXPECT_TRUE(sh::atm_ray_hits_ground(a, float(r), float(muh - eps))) << h << " " << eps;
            EXPECT_FALSE(sh::atm_ray_hits_ground(a, float(r), float(muh + eps))) << h << " " << eps;
        }
        // Just below the horizon the ray ends on the ground sphere.
        const float dg = sh::atm_distance_to_ground(a, float(r), float(muh - 1e-3));
        EXPECT_GT(dg, 0.0f);
        EXPECT_NEAR(sh::atm_radius_at(float(r), float(muh - 1e-3), dg), a.bottom_radius_m, 2.0) << h;
        // At +-1e-6 from the horizon (float): the decision still follows the sign.
        if (h >= 10.0) {
            EXPECT_TRUE(sh::atm_ray_hits_ground(a, float(r), float(muh - 1e-6))) << h;
            EXPECT_FALSE(sh::atm_ray_hits_ground(a, float(r), float(muh + 1e-6))) << h;
        }
    }
}

// shared/ray_sphere.glsl is one routine in two precisions: the float build (the GPU's and the
// production model's) follows the double one the reference integrator runs, to float rounding,
// and makes the same ground decision away from the horizon.
TEST(ProductionToy, RaySphereFloatFollowsTheDoubleReference) {
    const double R = 6360000.0, top = 6420000.0;
    int decisions = 0;
    for (double h : {1.0, 150.0, 2000.0, 30000.0, 59000.0}) {
        const double r = R + h;
        const double muh = at::f64::ray_sphere_horizon_mu(r, R);
        EXPECT_NEAR(sh::ray_sphere_horizon_mu(float(r), float(R)), muh, 1e-5) << h;
        for (double mu = -1.0; mu <= 1.0; mu += 0.0625) {
            const float rf = float(r), mf = float(mu);
            const double far = at::f64::ray_sphere_far_m(rf, mf, top);
            EXPECT_NEAR(sh::ray_sphere_far_m(rf, mf, float(top)), far, 2.0 + 1e-6 * far) << h << " " << mu;
            if (std::abs(mu - muh) < 1e-3) continue;  // float's own decision at the horizon: tested above
            const bool hits = at::f64::ray_hits_sphere(rf, mf, R);
            EXPECT_EQ(sh::ray_hits_sphere(rf, mf, float(R)), hits) << h << " " << mu;
            if (hits) {
                EXPECT_NEAR(sh::ray_sphere_near_m(rf, mf, float(R)), at::f64::ray_sphere_near_m(rf, mf, R),
                            2.0 + 1e-6 * at::f64::ray_sphere_near_m(rf, mf, R))
                    << h << " " << mu;
                ++decisions;
            }
        }
    }
    EXPECT_GT(decisions, 20);
}

TEST(ProductionToy, PhaseFunctionsIntegrateToOne) {
    for (double g : {0.0, 0.5, 0.8, 0.95}) {
        double ray = 0.0, cs = 0.0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            const double nu = -1.0 + 2.0 * (i + 0.5) / n;
            ray += sh::atm_rayleigh_phase(float(nu));
            cs += sh::atm_cornette_shanks_phase(float(g), float(nu));
        }
        EXPECT_NEAR(ray * 2.0 * M_PI * 2.0 / n, 1.0, 1e-4);
        EXPECT_NEAR(cs * 2.0 * M_PI * 2.0 / n, 1.0, g > 0.9 ? 2e-3 : 1e-4) << g;
    }
}

// ---------------------------------------------------------------- table mappings

TEST(ProductionTables, TransmittanceMappingRoundTripsAtTexelCentresAndEdges) {
    const sh::AtmosphereParams a = at::to_shader_params(at::AtmosphereParameters::earth());
    const glm::vec2 size(256.0f, 64.0f);
    for (int j = 0; j <= 2 * 64; ++j)
        for (int i = 0; i <= 2 * 256; i += 3) {
            // Even indices are texel edges, odd ones texel centres (edges outside [0.5/n, 1 - 0.5/n]
            // clamp to the end rows by design, so only the inner range round-trips).
            const glm::vec2 uv(i / (2.0f * size.x), j / (2.0f * size.y));
            if (uv.x < 0.5f / size.x || uv.x > 1.0f - 0.5f / size.x || uv.y < 0.5f / size.y ||
                uv.y > 1.0f - 0.5f / size.y)
                continue;
            const glm::vec2 rm = sh::atm_transmittance_r_mu(a, uv, size);
            const glm::vec2 back = sh::atm_transmittance_uv(a, rm.x, rm.y, size);
            // Within 10 % of a texel: float r has a 0.5 m ulp, which is all that is lost (it matters only
            // in the rows a few metres above the ground).
            EXPECT_NEAR(back.x, uv.x, 0.1 / size.x) << i << "," << j;
            EXPECT_NEAR(back.y, uv.y, 0.1 / size.y) << i << "," << j;
        }
    // The first and last texel centres are the ends of the parameter ranges.
    const glm::vec2 ground_horizon =
        sh::atm_transmittance_r_mu(a, glm::vec2(1.0f - 0.5f / size.x, 0.5f / size.y), size);
    EXPECT_NEAR(ground_horizon.x, a.bottom_radius_m, 1.0);
    EXPECT_NEAR(ground_horizon.y, 0.0, 1e-3);
    const glm::vec2 top_zenith = sh::atm_transmittance_r_mu(a, glm::vec2(0.5f / size.x, 1.0f - 0.5f / size.y), size);
    EXPECT_NEAR(top_zenith.x, a.top_radius_m, 1.0);
    EXPECT_NEAR(top_zenith.y, 1.0, 1e-6);
}

TEST(ProductionTables, MultipleScatteringMappingRoundTrips) {
    const sh::AtmosphereParams a = at::to_shader_params(at::AtmosphereParameters::mars());
    const glm::vec2 size(32.0f, 32.0f);
    for (int j = 1; j < 64; ++j)
        for (int i = 1; i < 64; ++i) {
            const glm::vec2 uv(i / 64.0f, j / 64.0f);
            if (uv.x < 0.5f / 32 || uv.x > 1 - 0.5f / 32 || uv.y < 0.5f / 32 || uv.y > 1 - 0.5f / 32) continue;
            const glm::vec2 rs = sh::atm_ms_r_mu_s(a, uv, size);
            const glm::vec2 back = sh::atm_ms_uv(a, rs.x, rs.y, size);
            EXPECT_NEAR(back.x, uv.x, 1e-5);
            EXPECT_NEAR(back.y, uv.y, 1e-4);
        }
    EXPECT_NEAR(sh::atm_ms_r_mu_s(a, glm::vec2(0.5f / 32, 0.5f / 32), size).y, -1.0, 1e-6);
    EXPECT_NEAR(sh::atm_ms_r_mu_s(a, glm::vec2(1 - 0.5f / 32, 1 - 0.5f / 32), size).x, a.top_radius_m, 1.0);
}

TEST(ProductionTables, SamplerMatchesTexelValuesAtCentresAndInterpolatesBetween) {
    sh::Texture2DData t;
    t.width = 2;
    t.height = 1;
    t.texels = {glm::vec4(1.0f), glm::vec4(3.0f)};
    const sh::sampler2D s{&t};
    EXPECT_FLOAT_EQ(sh::textureLod(s, glm::vec2(0.25f, 0.5f), 0.0).x, 1.0f);
    EXPECT_FLOAT_EQ(sh::textureLod(s, glm::vec2(0.75f, 0.5f), 0.0).x, 3.0f);
    EXPECT_FLOAT_EQ(sh::textureLod(s, glm::vec2(0.5f, 0.5f), 0.0).x, 2.0f);
    EXPECT_FLOAT_EQ(sh::textureLod(s, glm::vec2(0.0f, 0.5f), 0.0).x, 1.0f);  // clamp to edge
}

TEST(ProductionTables, TransmittanceTableIs32BitAndMatchesDirectIntegration) {
    const at::ProductionAtmosphere m(at::AtmosphereParameters::earth(), at::production_quality("medium"), no_cache());
    const sh::AtmosphereParams& a = m.shader_params();
    const sh::sampler2D trans{&m.tables().transmittance};
    const glm::vec2 size(m.tables().transmittance.width, m.tables().transmittance.height);
    for (double h : {0.0, 3000.0, 30000.0})
        for (double mu : {1.0, 0.5, 0.1, 0.02}) {
            const float r = float(a.bottom_radius_m + h);
            const glm::vec3 lut = sh::atm_lookup_transmittance(a, trans, size, r, float(mu));
            const glm::vec3 direct = sh::atm_compute_transmittance(a, r, float(mu), 400);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(lut[c], direct[c], 5e-3 * direct[c] + 1e-6) << h << " " << mu;
        }
}

// The Rayleigh anisotropy of the multiple scattering (atm_ms_rayleigh_factor): the ratio in the
// table's alpha is a P2 moment of non-negative light over at least its own mean, so within
// [-1/2, 1]; the factor averages to 1 over all views (P2 has mean 0: no energy gained or lost);
// a level without it keeps alpha 0, factor 1, and another cache key.
TEST(ProductionTables, MultipleScatteringAnisotropyRatioIsBoundedAndKeepsTheMean) {
    at::ProductionQuality q = at::production_quality("low");
    q.ms_rayleigh_anisotropy = true;
    const at::ProductionAtmosphere on(at::AtmosphereParameters::earth(), q, no_cache());
    q.ms_rayleigh_anisotropy = false;
    const at::ProductionAtmosphere off(at::AtmosphereParameters::earth(), q, no_cache());
    float largest = 0.0f;
    for (const glm::vec4& v : on.tables().multiple_scattering.texels) {
        ASSERT_GE(v.w, -0.5f - 1e-5f);
        ASSERT_LE(v.w, 1.0f + 1e-5f);
        largest = std::max(largest, std::abs(v.w));
        double mean = 0.0;
        constexpr int kViews = 200;
        for (int i = 0; i < kViews; ++i) mean += sh::atm_ms_rayleigh_factor(v.w, -1.0f + (i + 0.5f) * 2.0f / kViews);
        ASSERT_NEAR(mean / kViews, 1.0, 1e-4);
    }
    EXPECT_GT(largest, 0.05f);  // the arriving light is anisotropic somewhere
    for (const glm::vec4& v : off.tables().multiple_scattering.texels) ASSERT_EQ(v.w, 0.0f);
    EXPECT_EQ(sh::atm_ms_rayleigh_factor(0.0f, 0.3f), 1.0f);
    EXPECT_NE(on.tables().cache_key, off.tables().cache_key);
}

TEST(ProductionTables, DiskCacheRoundTripsAndKeysOnParameters) {
    const std::string dir = scratch_dir("atmosphere_cache");
    at::TableCacheOptions cache;
    cache.directory = dir;
    const auto q = at::production_quality("low");
    const at::ProductionAtmosphere built(at::AtmosphereParameters::earth(), q, cache);
    EXPECT_FALSE(built.tables().from_cache);
    int exr = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) exr += e.path().extension() == ".exr";
    EXPECT_EQ(exr, 3);
    const at::ProductionAtmosphere loaded(at::AtmosphereParameters::earth(), q, cache);
    EXPECT_TRUE(loaded.tables().from_cache);
    ASSERT_EQ(loaded.tables().transmittance.texels.size(), built.tables().transmittance.texels.size());
    for (size_t i = 0; i < built.tables().transmittance.texels.size(); ++i)
        ASSERT_EQ(loaded.tables().transmittance.texels[i], built.tables().transmittance.texels[i]) << i;  // 32F exact
    for (size_t i = 0; i < built.tables().multiple_scattering.texels.size(); ++i)
        ASSERT_EQ(loaded.tables().multiple_scattering.texels[i], built.tables().multiple_scattering.texels[i]) << i;
    // A different atmosphere gets a different key (no stale reuse).
    auto p = at::AtmosphereParameters::earth();
    p.mie_g = 0.7;
    EXPECT_NE(at::table_cache_key(p, q), built.tables().cache_key);
    EXPECT_NE(at::table_cache_key(at::AtmosphereParameters::earth(), at::production_quality("medium")),
              built.tables().cache_key);
    // A damaged cache file is rebuilt, not trusted.
    for (const auto& e : std::filesystem::directory_iterator(dir)) cupola::test::write_text(e.path().string(), "junk");
    const at::ProductionAtmosphere rebuilt(at::AtmosphereParameters::earth(), q, cache);
    EXPECT_FALSE(rebuilt.tables().from_cache);
}

TEST(ProductionModel, UnknownQualityNameIsRejectedWithTheList) {
    try {
        at::production_quality("fastest");
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("medium"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("fastest"), std::string::npos);
    }
}

// ---------------------------------------------------------------- hard cases

namespace {
void expect_hard_cases_finite(const std::string& level);
}  // namespace

TEST(ProductionHardCases, NoNanOrInfAndBoundedAtTheHardGeometries) { expect_hard_cases_finite("medium"); }

// The sky-view level: every hard case looked up in its table (built for each camera and Sun).
TEST(ProductionHardCases, NoNanOrInfAndBoundedAtTheHardGeometriesSkyView) { expect_hard_cases_finite("sky-view"); }

namespace {
void expect_hard_cases_finite(const std::string& level) {
    const at::ProductionAtmosphere m(at::AtmosphereParameters::earth(), at::production_quality(level), no_cache());
    const auto& p = m.parameters();
    std::vector<at::SkyQuery> qs;
    for (double alt : {0.0, 1.0, 1000.0, p.top_radius - p.bottom_radius, 400000.0}) {
        const double r = p.bottom_radius + std::max(alt, 1.0);
        const double muh = -std::sqrt(std::max(0.0, 1.0 - std::pow(p.bottom_radius / r, 2)));
        for (double eps : {0.0, 1e-6, -1e-6, 1e-4, -1e-4, 4e-3, -4e-3})
            for (double sz : {0.0, 90.0, 100.0})
                qs.push_back({alt, glm::degrees(std::acos(std::clamp(muh + eps, -1.0, 1.0))), sz, 0.0});
    }
    for (double sz : {0.0, 30.0, 90.0, 100.0}) qs.push_back({1.496e11, 179.9995, sz, 0.0});  // 1 AU, at the planet
    for (const auto& q : qs) {
        const at::ProductionRadiance r = m.sky(q);
        ASSERT_TRUE(finite_nonnegative(r.xyz)) << q.altitude_m << " " << q.view_zenith_deg << " " << q.sun_zenith_deg;
        EXPECT_LT(r.luminance, 1e5) << q.altitude_m << " " << q.view_zenith_deg;  // bounded: brighter than any sky
    }
    // Both sides of the horizon stay continuous at the ground: the ±1e-6 pair differ by the ground's
    // contribution only (no blow-up from the split).
    const double r0 = p.bottom_radius + 1.0;
    const double muh = -std::sqrt(1.0 - std::pow(p.bottom_radius / r0, 2));
    const auto above = m.sky({0.0, glm::degrees(std::acos(muh + 1e-6)), 60.0, 0.0});
    const auto above2 = m.sky({0.0, glm::degrees(std::acos(muh + 4e-3)), 60.0, 0.0});
    EXPECT_NEAR(above.luminance, above2.luminance, 0.2 * above2.luminance) << level;
}
}  // namespace

TEST(ProductionHardCases, GeometryAFewMetresAwayWithTheSunAtTheHorizon) {
    const at::ProductionAtmosphere m(at::AtmosphereParameters::earth(), at::production_quality("medium"), no_cache());
    const sh::AtmosphereParams& a = m.shader_params();
    for (double sun_elev : {0.0, 0.2, -0.2})
        for (float dist : {0.5f, 2.0f, 5.0f, 20.0f}) {
            const double s = glm::radians(sun_elev);
            const glm::vec3 sun(float(std::cos(s)), 0.0f, float(std::sin(s)));
            const glm::vec3 v = glm::normalize(glm::vec3(0.8f, 0.6f, -0.01f));
            const auto st = sh::atm_ray_start(a, a.bottom_radius_m + 1.5f, v, glm::vec3(0, 0, -1), sun);
            glm::vec3 t;
            const glm::vec3 f = m.radiance(st, dist, &t);
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(f[c]) && f[c] >= 0.0f) << dist;
                EXPECT_GT(t[c], 0.99f);  // a few metres of air barely attenuate
                EXPECT_LE(t[c], 1.0f);
            }
            // In-scatter over a few metres is tiny compared with the open sky.
            glm::vec3 t_sky;
            const glm::vec3 sky = m.radiance(st, -1.0f, &t_sky);
            EXPECT_LT(f.y, 0.01f * sky.y + 1e-12f) << dist << " " << sun_elev;
        }
}

TEST(ProductionHardCases, SunBelowTheHorizonDarkensTheGroundSky) {
    const at::ProductionAtmosphere m(at::AtmosphereParameters::earth(), at::production_quality("medium"), no_cache());
    const double noon = m.sky({0.0, 45.0, 0.0, 90.0}).luminance;
    const double horizon = m.sky({0.0, 45.0, 90.0, 90.0}).luminance;
    const double night = m.sky({0.0, 45.0, 100.0, 90.0}).luminance;
    EXPECT_GT(noon, 5.0 * horizon);
    EXPECT_GT(horizon, 10.0 * night);
    EXPECT_GE(night, 0.0);
}

// ---------------------------------------------------------------- against the reference

namespace {
const at::ReferenceDataset& earth_reference() {
    static const at::ReferenceDataset d =
        at::read_reference_dataset(source_path("data/atmosphere/earth_reference.csv"));
    return d;
}

void print_report(const std::string& level, const at::AccuracyReport& r) {
    std::printf("%s: %-7s %5s %5s %8s %8s %8s %8s %8s\n", level.c_str(), "camera", "sun", "n", "median", "p99", "bias",
                "duv_med", "duv_p99");
    for (const auto& g : r.groups)
        std::printf("%s: %-7s %5.0f %5d %8.4f %8.4f %+8.4f %8.4f %8.4f\n", level.c_str(), g.camera.c_str(),
                    g.sun_zenith_deg, g.used, g.median, g.p99, g.mean_signed, g.chroma_median, g.chroma_p99);
    std::printf(
        "%s: overall n %d (reference-limited %d, missing the atmosphere %d) median %.4f p99 %.4f duv median %.4f p99 "
        "%.4f\n",
        level.c_str(), r.overall.used, r.overall.reference_limited, r.overall.skipped, r.overall.median, r.overall.p99,
        r.overall.chroma_median, r.overall.chroma_p99);
}
}  // namespace

TEST(ProductionVsReference, DefaultModelMeetsTheErrorTargetsOverall) {
    const auto& ref = earth_reference();
    ASSERT_EQ(ref.hash, at::AtmosphereParameters::earth().hash_hex()) << "stale reference dataset";
    const at::ProductionAtmosphere m(at::AtmosphereParameters::earth(),
                                     at::production_quality(at::kDefaultProductionQuality), no_cache());
    const at::AccuracyReport r = at::measure_accuracy(m, ref);
    print_report(at::kDefaultProductionQuality, r);
    ASSERT_EQ(r.groups.size(), 20u);  // 5 cameras x 4 suns
    for (const auto& g : r.groups) {
        EXPECT_GE(g.used + g.skipped + g.reference_limited, 500) << g.camera << " " << g.sun_zenith_deg;
        EXPECT_EQ(g.nonzero_where_reference_is_zero, 0) << g.camera << " " << g.sun_zenith_deg;
    }
    // Every daylight set is measured (the reference is precise there).
    for (const auto& g : r.groups)
        if (g.sun_zenith_deg < 80.0) {
            EXPECT_EQ(g.reference_limited, 0) << g.camera << " " << g.sun_zenith_deg;
        }
    EXPECT_LE(r.overall.median, 0.02);
    // The target is 10 %, twilight rows counted: the default level reaches 6.5 %
    // (test_atmosphere_sky_view.cpp guards the figures; docs/atmosphere-speed-vs-error.md).
    EXPECT_LE(r.overall.p99, 0.10);
    EXPECT_LE(r.overall.chroma_median, 0.005);  // about one just-noticeable difference
}

TEST(ProductionVsReference, TheAnalyticFastModeIsMeasuredAndWorseThanTheTables) {
    const auto& ref = earth_reference();
    const at::ProductionAtmosphere fast(at::AtmosphereParameters::earth(), at::production_quality("analytic"),
                                        no_cache());
    const at::ProductionAtmosphere def(at::AtmosphereParameters::earth(), at::production_quality("medium"), no_cache());
    const at::AccuracyReport rf = at::measure_accuracy(fast, ref), rd = at::measure_accuracy(def, ref);
    print_report("analytic", rf);
    EXPECT_GT(rf.overall.median, rd.overall.median);
    EXPECT_TRUE(std::isfinite(rf.overall.p99));
}

TEST(ProductionMars, DustySkyIsReddishAndTracksTheReference) {
    const at::ProductionAtmosphere m(at::AtmosphereParameters::mars(), at::production_quality("medium"), no_cache());
    at::ReferenceSettings rs;
    rs.ms_paths = 1024;
    rs.scattering_orders = 12;  // optical depth ~0.5 of dust: high orders matter near the horizon
    const at::ReferenceIntegrator ref(at::AtmosphereParameters::mars(), rs);
    for (const at::SkyQuery q : {at::SkyQuery{0.0, 45.0, 30.0, 90.0}, at::SkyQuery{0.0, 80.0, 60.0, 180.0},
                                 at::SkyQuery{0.0, 60.0, 45.0, 0.0}}) {
        const at::ProductionRadiance p = m.sky(q);
        const at::SkyRadiance r = ref.sky(q);
        std::printf("mars vz %.0f sz %.0f az %.0f: production %.4g reference %.4g cd/m^2, rgb %.3g %.3g %.3g\n",
                    q.view_zenith_deg, q.sun_zenith_deg, q.relative_azimuth_deg, p.luminance, r.luminance, p.rgb.r,
                    p.rgb.g, p.rgb.b);
        EXPECT_GT(p.rgb.r, p.rgb.b);  // butterscotch, not blue: the dust's albedo falls toward the blue
        EXPECT_GT(r.rgb.r, r.rgb.b);
        // Known weakness, measured and documented (docs/atmosphere-speed-vs-error.md): Mars' dust
        // (optical depth 0.5, g 0.65) scatters many times and keeps its forward peak, which the
        // isotropic multiple-scattering table cannot follow: -15 % toward the Sun, +40 % low in the
        // anti-solar sky. The bound guards against regressions beyond that.
        EXPECT_NEAR(p.luminance, r.luminance, 0.5 * r.luminance);
    }
}

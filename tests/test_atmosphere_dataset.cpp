// Tests of the atmosphere validation set (common/atmosphere/validation_set.hpp), of the reference
// dataset format (common/atmosphere/reference_dataset.hpp) and of the committed dataset
// data/atmosphere/earth_reference.csv: it must belong to the current Earth preset, hold every
// validation case in order, and a sample of its rows must be reproduced by the reference
// integrator with the recorded settings (so a stale or hand-edited file fails).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "atmosphere/atmosphere_geometry.hpp"
#include "atmosphere/atmosphere_parameters.hpp"
#include "atmosphere/production_accuracy.hpp"
#include "atmosphere/reference_dataset.hpp"
#include "atmosphere/reference_integrator.hpp"
#include "atmosphere/validation_set.hpp"
#include "support/test_support.hpp"

namespace at = cupola::atmosphere;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const char* const kDatasetPath = "data/atmosphere/earth_reference.csv";

std::size_t index_of(const std::string& camera, double sun_zenith_deg, int direction, int directions) {
    const auto& cams = at::validation_cameras();
    const auto& suns = at::validation_sun_zeniths_deg();
    const std::size_t c = std::find(cams.begin(), cams.end(), camera) - cams.begin();
    const std::size_t s = std::find(suns.begin(), suns.end(), sun_zenith_deg) - suns.begin();
    return (c * suns.size() + s) * directions + direction;
}

bool same_case(const at::ValidationCase& a, const at::ValidationCase& b) {
    return a.camera == b.camera && a.query.altitude_m == b.query.altitude_m &&
           a.query.view_zenith_deg == b.query.view_zenith_deg && a.query.sun_zenith_deg == b.query.sun_zenith_deg &&
           a.query.relative_azimuth_deg == b.query.relative_azimuth_deg;
}

void expect_relative(double stored, double computed, double tol, const std::string& what) {
    EXPECT_LE(std::abs(stored - computed), tol * std::max(std::abs(stored), std::abs(computed)))
        << what << ": stored " << stored << ", recomputed " << computed;
}

// A valid two-row dataset text, for the reader tests.
std::string small_dataset_text() {
    at::ReferenceDataset d;
    d.preset = "earth";
    d.hash = "00ff";
    d.orders = 2;
    d.paths = 16;
    d.seed = 7;
    d.directions = 1;
    d.metadata = {{"command", "test"}};
    for (const auto& c : at::validation_set(at::AtmosphereParameters::earth(), 1)) {
        if (d.rows.size() == 2) break;
        at::ReferenceRow r;
        r.c = c;
        r.luminance = 1234.5678901234;
        r.luminance_stderr = 0.5;
        r.rgb = {1.0, 2.0, 3.0};
        r.xyz = {4.0, 1234.5678901234, -1e-3};
        d.rows.push_back(r);
    }
    std::ostringstream out;
    at::write_reference_dataset(out, d, {"a free comment, with = and commas"});
    return out.str();
}

}  // namespace

// ---------------------------------------------------------------- validation set

TEST(ValidationSet, SizesOrderAndDeterminism) {
    const auto p = at::AtmosphereParameters::earth();
    const auto set = at::validation_set(p);
    ASSERT_EQ(set.size(), 5u * 4u * 512u);
    EXPECT_EQ(at::validation_set(p, 7).size(), 5u * 4u * 7u);
    EXPECT_THROW(at::validation_set(p, 0), std::invalid_argument);

    const auto again = at::validation_set(p);
    for (std::size_t i = 0; i < set.size(); ++i) ASSERT_TRUE(same_case(set[i], again[i])) << i;

    for (const std::string& cam : at::validation_cameras())
        for (double sun : at::validation_sun_zeniths_deg())
            for (int i : {0, 511}) {
                const auto& c = set[index_of(cam, sun, i, 512)];
                EXPECT_EQ(c.camera, cam);
                EXPECT_EQ(c.query.sun_zenith_deg, sun);
                EXPECT_EQ(c.query.altitude_m, at::validation_camera_altitude(cam));
            }
    EXPECT_EQ(set.front().query.altitude_m, at::kMinCameraAltitude);
    EXPECT_EQ(at::validation_camera_altitude("limb"), 400000.0);
}

TEST(ValidationSet, AllFiniteAndInRange) {
    for (const auto& p : {at::AtmosphereParameters::earth(), at::AtmosphereParameters::mars()})
        for (const auto& c : at::validation_set(p)) {
            const auto& q = c.query;
            ASSERT_TRUE(std::isfinite(q.altitude_m) && std::isfinite(q.view_zenith_deg) &&
                        std::isfinite(q.sun_zenith_deg) && std::isfinite(q.relative_azimuth_deg));
            ASSERT_GE(q.view_zenith_deg, 0.0);
            ASSERT_LE(q.view_zenith_deg, 180.0);
            ASSERT_GE(q.relative_azimuth_deg, -180.0);
            ASSERT_LT(q.relative_azimuth_deg, 180.0);
        }
}

TEST(ValidationSet, CamerasInsideCoverTheWholeSphere) {
    const auto p = at::AtmosphereParameters::earth();
    const auto set = at::validation_set(p);
    for (const std::string cam : {"ground", "10km"}) {
        ASSERT_LE(p.bottom_radius + at::validation_camera_altitude(cam), p.top_radius);
        double mean_mu = 0.0, mean_cos_az = 0.0, min_vz = 180.0, max_vz = 0.0;
        int below_horizon = 0;
        for (int i = 0; i < 512; ++i) {
            const auto& q = set[index_of(cam, 65.0, i, 512)].query;
            mean_mu += std::cos(q.view_zenith_deg * kDeg) / 512;
            mean_cos_az += std::cos(q.relative_azimuth_deg * kDeg) / 512;
            min_vz = std::min(min_vz, q.view_zenith_deg);
            max_vz = std::max(max_vz, q.view_zenith_deg);
            below_horizon += q.view_zenith_deg > 90.0;
        }
        EXPECT_NEAR(mean_mu, 0.0, 1e-9) << cam;  // uniform in solid angle (symmetric lattice)
        EXPECT_NEAR(mean_cos_az, 0.0, 0.01) << cam;
        EXPECT_LT(min_vz, 5.0) << cam;
        EXPECT_GT(max_vz, 175.0) << cam;
        EXPECT_EQ(below_horizon, 256) << cam;
    }
}

TEST(ValidationSet, CamerasOutsideAllMeetTheAtmosphere) {
    for (const auto& p : {at::AtmosphereParameters::earth(), at::AtmosphereParameters::mars()}) {
        const double R = p.bottom_radius, top = p.top_radius;
        for (const auto& c : at::validation_set(p)) {
            const double r = R + c.query.altitude_m;
            if (r <= top) continue;
            const double mu = std::cos(c.query.view_zenith_deg * kDeg);
            EXPECT_TRUE(at::enter_atmosphere(r, mu, R, top).intersects) << p.name << " " << c.camera;
        }
        // The cap is covered from near-tangent to nadir.
        const auto set = at::validation_set(p);
        for (const std::string cam : {"100km", "1000km"}) {
            const double r = R + at::validation_camera_altitude(cam);
            ASSERT_GT(r, top) << p.name << " " << cam;
            const double tangent_vz = 180.0 - std::asin(top / r) / kDeg;
            double min_vz = 180.0, max_vz = 0.0;
            for (int i = 0; i < 512; ++i) {
                const double vz = set[index_of(cam, 30.0, i, 512)].query.view_zenith_deg;
                min_vz = std::min(min_vz, vz);
                max_vz = std::max(max_vz, vz);
            }
            EXPECT_GT(min_vz, tangent_vz);
            EXPECT_LT(min_vz, tangent_vz + 1.0) << p.name << " " << cam;
            // The lattice's first point sits half a step of the cap's 1 + mu range from nadir.
            const double half_step = 0.5 * (1.0 - std::sqrt((r - top) * (r + top)) / r) / 512;
            EXPECT_NEAR(max_vz, 180.0 - std::acos(1.0 - half_step) / kDeg, 1e-9) << p.name << " " << cam;
        }
    }
}

TEST(ValidationSet, LimbBandRaysGrazeTheRim) {
    for (const auto& p : {at::AtmosphereParameters::earth(), at::AtmosphereParameters::mars()}) {
        const double R = p.bottom_radius, top = p.top_radius;
        const double r = R + at::validation_camera_altitude("limb");
        const double horizon_vz = 180.0 - std::asin(R / r) / kDeg;
        const double tangent_vz = 180.0 - std::asin(top / r) / kDeg;
        int hits = 0, misses = 0;
        for (const auto& c : at::validation_set(p)) {
            if (c.camera != "limb") continue;
            const double vz = c.query.view_zenith_deg, mu = std::cos(vz * kDeg);
            ASSERT_GT(vz, tangent_vz);               // below the ray tangent to the top sphere
            ASSERT_LT(vz, horizon_vz + 2.0 + 1e-9);  // at most 2 deg below the ground horizon
            ASSERT_TRUE(at::enter_atmosphere(r, mu, R, top).intersects);
            // Closest approach of the (extended) ray: below the top of the atmosphere, and for the
            // rays that hit the ground, within the 2 deg band (a few tens of km "under" the rim).
            const double closest_altitude = r * std::sin(vz * kDeg) - R;
            ASSERT_LT(closest_altitude, top - R);
            ASSERT_GT(closest_altitude, -0.05 * R);
            (at::f64::ray_hits_sphere(r, mu, R) ? hits : misses)++;
        }
        EXPECT_GT(hits, 100) << p.name;
        EXPECT_GT(misses, 100) << p.name;
    }
}

// ---------------------------------------------------------------- dataset format

TEST(ReferenceDatasetFormat, RoundTrips) {
    const std::string path = cupola::test::scratch_dir("atmosphere_dataset_roundtrip") + "/small.csv";
    cupola::test::write_text(path, small_dataset_text());
    const at::ReferenceDataset d = at::read_reference_dataset(path);
    EXPECT_EQ(d.preset, "earth");
    EXPECT_EQ(d.hash, "00ff");
    EXPECT_EQ(d.orders, 2);
    EXPECT_EQ(d.paths, 16);
    EXPECT_EQ(d.seed, 7u);
    EXPECT_EQ(d.directions, 1);
    EXPECT_EQ(d.metadata.at("command"), "test");
    ASSERT_EQ(d.rows.size(), 2u);
    const auto set = at::validation_set(at::AtmosphereParameters::earth(), 1);
    EXPECT_TRUE(same_case(d.rows[1].c, set[1]));
    EXPECT_EQ(d.rows[1].luminance, 1234.56789);  // %.9g
    EXPECT_EQ(d.rows[1].xyz.z, -1e-3);
}

TEST(ReferenceDatasetFormat, RejectsMalformedInputNamingTheLine) {
    const std::string dir = cupola::test::scratch_dir("atmosphere_dataset_malformed");
    const std::string good = small_dataset_text();
    std::vector<std::string> lines;
    std::istringstream in(good);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    const std::size_t header = std::find(lines.begin(), lines.end(), at::kReferenceCsvHeader) - lines.begin();
    ASSERT_LT(header + 2, lines.size());
    auto join = [](const std::vector<std::string>& v) {
        std::string s;
        for (const auto& l : v) s += l + "\n";
        return s;
    };
    auto expect_error = [&](const std::vector<std::string>& v, std::size_t bad_index, const std::string& fragment,
                            const std::string& label) {
        const std::string path = dir + "/" + label + ".csv";
        cupola::test::write_text(path, join(v));
        try {
            at::read_reference_dataset(path);
            ADD_FAILURE() << label << ": accepted";
        } catch (const std::runtime_error& e) {
            const std::string where = path + ":" + std::to_string(bad_index + 1) + ":";
            EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << label << ": " << e.what();
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << label << ": " << e.what();
        }
    };
    const std::size_t row = header + 2;  // the second data row

    auto bad_number = lines;
    bad_number[row].replace(bad_number[row].find(",1234.56789,"), 12, ",12x4.5,");
    expect_error(bad_number, row, "luminance", "bad_number");

    auto missing_field = lines;
    missing_field[row] = missing_field[row].substr(0, missing_field[row].rfind(','));
    expect_error(missing_field, row, "fields", "missing_field");

    auto bad_flag = lines;
    bad_flag[row].replace(bad_flag[row].find(",0,1,"), 5, ",2,1,");
    expect_error(bad_flag, row, "hits_ground", "bad_flag");

    auto bad_header = lines;
    bad_header[header] = "camera,altitude";
    expect_error(bad_header, header, "header", "bad_header");

    auto no_hash = lines;
    const std::size_t hash_line = std::find(lines.begin(), lines.end(), "# hash=00ff") - lines.begin();
    ASSERT_LT(hash_line, header);
    no_hash.erase(no_hash.begin() + hash_line);
    expect_error(no_hash, header - 1, "hash", "no_hash");

    EXPECT_THROW(at::read_reference_dataset(dir + "/does_not_exist.csv"), std::runtime_error);
}

// ---------------------------------------------------------------- the committed dataset

class EarthReferenceDataset : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        const std::string path = cupola::test::source_path(kDatasetPath);
        if (std::filesystem::exists(path)) dataset_ = new at::ReferenceDataset(at::read_reference_dataset(path));
    }
    static void TearDownTestSuite() {
        delete dataset_;
        dataset_ = nullptr;
    }
    void SetUp() override { ASSERT_NE(dataset_, nullptr) << kDatasetPath << " is missing"; }
    static const at::ReferenceDataset& d() { return *dataset_; }

private:
    static inline at::ReferenceDataset* dataset_ = nullptr;
};

TEST_F(EarthReferenceDataset, BelongsToTheCurrentEarthPreset) {
    EXPECT_EQ(d().preset, "earth");
    EXPECT_EQ(d().hash, at::AtmosphereParameters::earth().hash_hex())
        << "the Earth preset changed: regenerate the dataset (data/atmosphere/PROVENANCE.md)";
}

TEST_F(EarthReferenceDataset, HoldsEveryValidationCaseInOrder) {
    const auto p = at::AtmosphereParameters::earth();
    const auto set = at::validation_set(p, d().directions);
    ASSERT_EQ(d().rows.size(), set.size());
    for (std::size_t i = 0; i < set.size(); ++i) {
        const auto& row = d().rows[i];
        ASSERT_TRUE(same_case(row.c, set[i])) << "row " << i;
        ASSERT_TRUE(row.in_atmosphere) << "row " << i;
        ASSERT_GE(row.luminance, 0.0) << "row " << i;
        ASSERT_GE(row.luminance_stderr, 0.0) << "row " << i;
        const double r = p.bottom_radius + std::max(row.c.query.altitude_m, at::kMinCameraAltitude);
        const auto e =
            at::enter_atmosphere(r, std::cos(row.c.query.view_zenith_deg * kDeg), p.bottom_radius, p.top_radius);
        ASSERT_EQ(row.hits_ground, at::f64::ray_hits_sphere(e.r_m, e.mu, p.bottom_radius)) << "row " << i;
    }
}

TEST_F(EarthReferenceDataset, SampledRowsAreReproduced) {
    const int n = d().directions;
    // Spread over the file: every camera, every sun zenith, twilight (95 deg) and the limb included.
    const std::vector<std::size_t> sample = {
        index_of("ground", 30.0, 0, n),    index_of("ground", 95.0, n / 3, n), index_of("10km", 65.0, n - 1, n),
        index_of("100km", 88.0, n / 2, n), index_of("1000km", 30.0, n / 5, n), index_of("limb", 95.0, (2 * n) / 3, n),
    };
    for (std::size_t i : sample) {
        ASSERT_LT(i, d().rows.size());
        const auto& row = d().rows[i];
        const at::ReferenceIntegrator ri(at::AtmosphereParameters::earth(),
                                         at::row_settings(d(), row.c.query.sun_zenith_deg));
        const at::SkyRadiance sky = ri.sky(row.c.query);
        const std::string what = "row " + std::to_string(i) + " (" + row.c.camera + ")";
        EXPECT_EQ(sky.hits_ground, row.hits_ground) << what;
        expect_relative(row.luminance, sky.luminance, 1e-6, what + " luminance");
        for (int k = 0; k < 3; ++k) expect_relative(row.rgb[k], sky.rgb[k], 1e-6, what + " rgb");
    }
}

TEST_F(EarthReferenceDataset, TwilightSetsArePreciseEnoughToJudgeAModel) {
    // measure_accuracy() leaves out the rows reference_is_limited() rejects (exactly 0, or Monte
    // Carlo noise above kMaxReferenceNoise). Of the rows that matter -- in the atmosphere, with a
    // reference of at least kLuminanceFloor -- every (camera, sun) group keeps at least 90 %,
    // the twilight groups (sun at 88 and 95 degrees) included, except the two orbital cameras
    // (1000 km, the limb) in twilight: much of what they see is the night side, lit only through
    // several scatterings from the distant twilight ring, and the reference keeps only 64-90 % of
    // those rows (the counts per group are in data/atmosphere/PROVENANCE.md); for them the bound
    // is 60 %. The median noise of every group is at most 3 %.
    constexpr double kMinKeptShare = 0.9, kMinKeptShareOrbitInTwilight = 0.6, kMaxMedianNoise = 0.03;
    struct Group {
        int bright = 0, kept = 0;
        std::vector<double> noise;
    };
    std::map<std::pair<std::string, double>, Group> groups;
    for (const auto& row : d().rows) {
        if (!row.in_atmosphere || !(row.luminance >= at::kLuminanceFloor)) continue;
        Group& g = groups[{row.c.camera, row.c.query.sun_zenith_deg}];
        ++g.bright;
        if (!at::reference_is_limited(row)) ++g.kept;
        g.noise.push_back(row.luminance_stderr / row.luminance);
    }
    ASSERT_EQ(groups.size(), 20u);
    for (auto& [key, g] : groups) {
        std::sort(g.noise.begin(), g.noise.end());
        const double median = g.noise[g.noise.size() / 2];
        std::printf("[ noise ] %-7s sun %3.0f: %3d of %3d rows above the floor kept, median noise %.4f\n",
                    key.first.c_str(), key.second, g.kept, g.bright, median);
        const bool orbit_twilight = (key.first == "1000km" || key.first == "limb") && key.second >= 88.0;
        EXPECT_GE(g.kept, (orbit_twilight ? kMinKeptShareOrbitInTwilight : kMinKeptShare) * g.bright)
            << key.first << " sun " << key.second;
        EXPECT_LE(median, kMaxMedianNoise) << key.first << " sun " << key.second;
    }
}

TEST(ReferenceDatasetFormat, RowSettingsFollowTheMetadata) {
    at::ReferenceDataset d;
    d.orders = 6;
    d.paths = 1024;
    d.seed = 3;
    // A file from before the line sample: the collision estimator, a fixed count.
    at::ReferenceSettings s = at::row_settings(d, 30.0);
    EXPECT_EQ(s.scattering_orders, 6);
    EXPECT_EQ(s.ms_paths, 1024);
    EXPECT_EQ(s.seed, 3u);
    EXPECT_EQ(s.ms_estimator, at::MsEstimator::kCollision);
    EXPECT_EQ(s.ms_max_paths, 0);
    // Partly recomputed: the listed suns use the ms_* keys, the others the kept_* ones.
    d.metadata = {{"ms_estimator", "lit_segment"},
                  {"ms_max_paths", "8192"},
                  {"ms_target_noise", "0.02"},
                  {"ms_target_floor", "0.0001"},
                  {"kept_orders", "5"},
                  {"kept_paths", "4096"},
                  {"kept_seed", "1"},
                  {"kept_ms_estimator", "collision"},
                  {"recomputed_sun_zenith_deg", "88,95"}};
    s = at::row_settings(d, 95.0);
    EXPECT_EQ(s.ms_estimator, at::MsEstimator::kLitSegment);
    EXPECT_EQ(s.ms_paths, 1024);
    EXPECT_EQ(s.ms_max_paths, 8192);
    EXPECT_DOUBLE_EQ(s.ms_target_noise, 0.02);
    EXPECT_DOUBLE_EQ(s.ms_target_floor, 1e-4);
    s = at::row_settings(d, 65.0);
    EXPECT_EQ(s.ms_estimator, at::MsEstimator::kCollision);
    EXPECT_EQ(s.scattering_orders, 5);
    EXPECT_EQ(s.ms_paths, 4096);
    EXPECT_EQ(s.seed, 1u);
    EXPECT_EQ(s.ms_max_paths, 0);
    // Malformed values name their key.
    for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
             {"ms_estimator", "fast"}, {"ms_max_paths", "8k"}, {"recomputed_sun_zenith_deg", "88;95"}}) {
        at::ReferenceDataset bad = d;
        bad.metadata[key] = value;
        try {
            (void)at::row_settings(bad, 95.0);
            ADD_FAILURE() << key << "=" << value << " accepted";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}

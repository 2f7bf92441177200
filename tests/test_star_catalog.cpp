// The committed star catalogue (data/stars/bright_stars.csv) and its loader.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "scene/star_catalog.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

const Star* find(const std::vector<Star>& stars, const std::string& name) {
    for (const auto& s : stars)
        if (s.name == name) return &s;
    return nullptr;
}

// RA h m s, Dec d m s (J2000, from SIMBAD / the Hipparcos catalogue).
void expect_position(const Star& s, double h, double m, double sec, double sign, double d, double dm, double ds) {
    const double ra = 15.0 * (h + m / 60 + sec / 3600) * kDeg;
    const double dec = sign * (d + dm / 60 + ds / 3600) * kDeg;
    EXPECT_NEAR(s.ra_rad, ra, 1e-5) << s.name;
    EXPECT_NEAR(s.dec_rad, dec, 1e-5) << s.name;
}
}  // namespace

TEST(StarCatalog, CountIsAboutNineThousandToMagnitudeSixPointFive) {
    const auto stars = load_star_catalog(test::source_path("data/stars/bright_stars.csv"));
    EXPECT_GT(stars.size(), 8000u);
    EXPECT_LT(stars.size(), 10000u);
    for (const auto& s : stars) ASSERT_LE(s.v_mag, 6.5f);
    const auto bright = load_star_catalog(test::source_path("data/stars/bright_stars.csv"), 2.0);
    EXPECT_GT(bright.size(), 40u);  // about 50 stars are brighter than V = 2
    EXPECT_LT(bright.size(), 120u);
}

TEST(StarCatalog, KnownStars) {
    const auto stars = load_star_catalog(test::source_path("data/stars/bright_stars.csv"));
    const Star* sirius = find(stars, "Sirius");
    const Star* vega = find(stars, "Vega");
    const Star* betelgeuse = find(stars, "Betelgeuse");
    ASSERT_TRUE(sirius && vega && betelgeuse);
    expect_position(*sirius, 6, 45, 8.917, -1, 16, 42, 58.02);
    EXPECT_NEAR(sirius->v_mag, -1.44, 0.02);
    expect_position(*vega, 18, 36, 56.336, +1, 38, 47, 1.28);
    EXPECT_NEAR(vega->v_mag, 0.03, 0.02);
    expect_position(*betelgeuse, 5, 55, 10.305, +1, 7, 24, 25.43);
    EXPECT_NEAR(betelgeuse->v_mag, 0.45, 0.1);
    EXPECT_NEAR(betelgeuse->b_minus_v, 1.50, 0.1);  // a red supergiant (Hipparcos B-V 1.50)
    EXPECT_EQ(stars.front().name, "Sirius");        // brightest first
}

TEST(StarCatalog, DirectionUsesEquatorialAxes) {
    Star s;
    EXPECT_NEAR(glm::distance(s.direction(), glm::dvec3(1, 0, 0)), 0.0, 1e-12);  // RA 0, Dec 0 = +x
    s.ra_rad = std::numbers::pi / 2;
    EXPECT_NEAR(glm::distance(s.direction(), glm::dvec3(0, 1, 0)), 0.0, 1e-12);  // RA 6h = +y
    s.dec_rad = std::numbers::pi / 2;
    EXPECT_NEAR(glm::distance(s.direction(), glm::dvec3(0, 0, 1)), 0.0, 1e-12);  // north pole = +z
    const auto stars = load_star_catalog(test::source_path("data/stars/bright_stars.csv"), 2.5);
    const Star* polaris = find(stars, "Polaris");
    ASSERT_TRUE(polaris);
    EXPECT_GT(polaris->direction().z, std::cos(1.0 * kDeg));  // within a degree of the pole
}

TEST(StarCatalog, MalformedLineNamesFileAndLine) {
    const std::string dir = test::scratch_dir("StarCatalogMalformed");
    const std::string file = dir + "/bad.csv";
    test::write_text(file, "# comment\nra_deg,dec_deg,vmag,bv,name\n10.0,20.0,1.0,0.5,Good\n10.0,abc,1.0,0.5,Bad\n");
    try {
        load_star_catalog(file);
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file + ":4"), std::string::npos) << what;
        EXPECT_NE(what.find("dec_deg"), std::string::npos) << what;
    }
    test::write_text(file, "ra_deg,dec_deg,vmag,bv,name\n10.0,95.0,1.0,0.5,Pole\n");
    EXPECT_THROW(load_star_catalog(file), std::runtime_error);
    test::write_text(file, "ra_deg,dec_deg,vmag,bv,name\n10.0,20.0,1.0\n");
    EXPECT_THROW(load_star_catalog(file), std::runtime_error);
    EXPECT_THROW(load_star_catalog(dir + "/missing.csv"), std::runtime_error);
}

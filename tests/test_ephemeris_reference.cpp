// Cupola's positions of the Sun, the Moon, the planets and Pluto against an independent ephemeris
// over 1900-2100: PyEphem's libastro (its own VSOP87, ELP 2000-82 and Pluto code, sharing none
// with ERFA or libnova), 40 instants per body in data/ephemeris/pyephem_reference.csv, written by
// tools/make_ephemeris_reference.py. Both sides give the astrometric geocentric place (light time,
// no aberration, J2000 axes) at the same TT instant. The acceptance bound is 1 arcmin; the worst
// separation per body is printed for docs/ephemeris-accuracy.md.
#include <gtest/gtest.h>

#include <erfa.h>
#include <erfam.h>

#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "scene/planet_series.hpp"
#include "scene/sky_positions.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

struct ReferencePlace {
    std::string body;
    double tt_jd = 0.0, ra_deg = 0.0, dec_deg = 0.0;
};

std::vector<ReferencePlace> read_reference() {
    std::istringstream in(test::read_text(test::source_path("data/ephemeris/pyephem_reference.csv")));
    std::string line;
    std::getline(in, line);  // header
    std::vector<ReferencePlace> rows;
    while (std::getline(in, line)) {
        std::istringstream f(line);
        ReferencePlace r;
        std::string field;
        std::getline(f, r.body, ',');
        std::getline(f, field, ',');
        r.tt_jd = std::stod(field);
        std::getline(f, field, ',');
        r.ra_deg = std::stod(field);
        std::getline(f, field, ',');
        r.dec_deg = std::stod(field);
        rows.push_back(r);
    }
    return rows;
}

double separation_arcsec(const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 ua = glm::normalize(a), ub = glm::normalize(b);
    return 2.0 * std::asin(0.5 * glm::length(ua - ub)) * ERFA_DR2AS;
}

glm::dvec3 unit_from_ra_dec(double ra_deg, double dec_deg) {
    double p[3];
    eraS2c(ra_deg * ERFA_DD2R, dec_deg * ERFA_DD2R, p);
    return {p[0], p[1], p[2]};
}

}  // namespace

TEST(EphemerisReference, EveryBodyIsWithinAnArcminuteFrom1900To2100) {
    const auto rows = read_reference();
    ASSERT_EQ(rows.size(), 400u);
    std::map<std::string, std::pair<double, double>> worst;  // body -> (arcsec, tt_jd)
    for (const auto& r : rows) {
        const glm::dvec3 ours = astrometric_geocentric_m(r.body, (r.tt_jd - ERFA_DJ00) * ERFA_DAYSEC);
        const double sep = separation_arcsec(ours, unit_from_ra_dec(r.ra_deg, r.dec_deg));
        EXPECT_LT(sep, 60.0) << r.body << " at TT JD " << r.tt_jd;
        if (sep > worst[r.body].first) worst[r.body] = {sep, r.tt_jd};
    }
    EXPECT_EQ(worst.size(), sky_body_names().size());  // every body Cupola knows was checked
    for (const auto& [body, w] : worst)
        std::printf("%-8s worst %6.2f arcsec at TT JD %.3f\n", body.c_str(), w.first, w.second);
}

TEST(EphemerisReference, ThePlanetsAreWithinFiveArcseconds) {
    // VSOP87 in full against libastro's truncated VSOP87: a regression to eraPlan94 (75-94" for
    // Jupiter, Saturn and Uranus) or a frame mix-up fails here even when it stays under 1'.
    for (const auto& r : read_reference()) {
        if (r.body == "sun" || r.body == "moon" || r.body == "pluto") continue;
        const glm::dvec3 ours = astrometric_geocentric_m(r.body, (r.tt_jd - ERFA_DJ00) * ERFA_DAYSEC);
        EXPECT_LT(separation_arcsec(ours, unit_from_ra_dec(r.ra_deg, r.dec_deg)), 5.0) << r.body << " " << r.tt_jd;
    }
}

TEST(PlanetSeries, InterpolatedNodesFollowTheSeries) {
    // The quarter-day cubic against the series itself, at random instants: within 1e-8 AU (1.5 km).
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> day(-36500.0, 36500.0);
    for (const char* name : {"mercury", "venus", "mars", "jupiter", "pluto"}) {
        const PlanetSeries p = planet_series_from_name(name);
        double worst_au = 0.0;
        for (int i = 0; i < 200; ++i) {
            const double d = day(rng);
            worst_au =
                std::max(worst_au, glm::length(planet_heliocentric_au(p, d) - planet_heliocentric_series_au(p, d)));
        }
        EXPECT_LT(worst_au, 1e-8) << name;
    }
    EXPECT_THROW(planet_series_from_name("vulcan"), std::invalid_argument);
}

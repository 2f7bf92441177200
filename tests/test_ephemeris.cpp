// Time scales, Earth orientation and apparent positions (ERFA-backed) against published values.
// Sources (also in docs/ephemeris-accuracy.md):
//   [M25b] Meeus, Astronomical Algorithms, 2nd ed. (1998), Example 25.b: Sun, 1992 Oct 13.0 TD,
//          apparent alpha = 198.378178 deg, delta = -7.783871 deg, R = 0.99760775 AU (full VSOP87).
//   [M47a] Meeus, Example 47.a: Moon, 1992 Apr 12.0 TD, alpha = 134.688470 deg,
//          delta = +13.768368 deg, Delta = 368409.7 km. W. Landsman's moonpos (astrolibR,
//          https://search.r-project.org/CRAN/refmans/astrolibR/html/moonpos.html) quotes the
//          same instant as 08h58m45.23s +13d46m06.1s, "within 1 arcsec of the Astronomical Almanac".
//   [M33a] Meeus, Example 33.a: Venus, 1992 Dec 20.0 TD, alpha = 21h04m41.454s, delta = -18d53m16.84s.
//   Delta T table: data/time/PROVENANCE.md (The Astronomical Almanac, pp. K8-K9).
#include <gtest/gtest.h>

#include <erfa.h>
#include <erfam.h>

#include <cmath>

#include "scene/eclipse_geometry.hpp"
#include "scene/ephemeris.hpp"
#include "scene/sim_time.hpp"
#include "scene/sky_positions.hpp"

using namespace cupola;

namespace {
double tt_from_jd(double jd_tt) { return (jd_tt - ERFA_DJ00) * ERFA_DAYSEC; }
double arcsec(double deg) { return deg * 3600.0; }
// Difference of two right ascensions in arcseconds of arc, wrapped to (-180, 180] deg.
double ra_diff_arcsec(double a, double b) { return arcsec(std::remainder(a - b, 360.0)); }
}  // namespace

TEST(TimeScales, LeapSecondEraUsesTaiMinusUtc) {
    // Across the 2016-12-31 leap second TAI-UTC goes 36 -> 37 s, so Delta T = 32.184 + TAI-UTC
    // goes 68.184 -> 69.184 s (UT1 taken as UTC).
    EXPECT_NEAR(delta_t_seconds(utc_iso_to_j2000_seconds("2016-12-31T12:00:00Z")), 68.184, 1e-9);
    EXPECT_NEAR(delta_t_seconds(utc_iso_to_j2000_seconds("2017-01-01T12:00:00Z")), 69.184, 1e-9);
    // 2006: TAI-UTC = 33 s, Delta T = 65.184 s (the measured value was 64.9-65.0 s; |UT1-UTC| < 0.9 s).
    const double t2006 = utc_iso_to_j2000_seconds("2006-03-29T10:11:00Z");
    EXPECT_NEAR(delta_t_seconds(t2006), 65.184, 1e-9);
    EXPECT_GT(delta_t_seconds(t2006), 64.0);
    EXPECT_LT(delta_t_seconds(t2006), 65.5);
    // UT1 = TT - Delta T.
    const JulianDate ut1 = tt_to_ut1_jd(t2006);
    EXPECT_NEAR(((ut1.jd1 - ERFA_DJ00) + ut1.jd2) * ERFA_DAYSEC, t2006 - 65.184, 1e-6);
    // The stored table agrees with the leap-second rule wherever both exist (1972-1995), to the
    // 0.9 s that UTC is allowed to stray from UT1.
    for (int year = 1972; year <= 1994; ++year) {
        const double t = utc_iso_to_j2000_seconds(std::to_string(year) + "-07-01T00:00:00Z");
        EXPECT_NEAR(tabulated_delta_t_seconds(year + 0.5), delta_t_seconds(t), 0.9) << year;
    }
}

// Past ERFA's leap seconds nobody has announced the leap seconds to come, but UTC will stay within
// 0.9 s of UT1: a time given there is the Earth's rotation (UT1), and TT = UT1 + Delta T. Taking
// TAI - UTC frozen at its last value instead made TT - Delta T drift from the time given by 40 s in
// 2058: a ground observer's sky turned 10 arcmin.
TEST(TimeScales, PastTheLeapSecondsTheTimeGivenIsTheEarthsRotation) {
    for (const char* iso : {"2040-07-20T09:37:23Z", "2058-04-28T12:45:42Z", "2100-01-01T00:00:00Z"}) {
        const double t = utc_iso_to_j2000_seconds(iso);
        int y, mo, d, h, mi;
        double s, d1, d2;
        ASSERT_EQ(std::sscanf(iso, "%d-%d-%dT%d:%d:%lfZ", &y, &mo, &d, &h, &mi, &s), 6);
        eraDtf2d("UT1", y, mo, d, h, mi, s, &d1, &d2);
        const JulianDate ut1 = tt_to_ut1_jd(t);
        EXPECT_NEAR(((ut1.jd1 - d1) + (ut1.jd2 - d2)) * ERFA_DAYSEC, 0.0, 1e-3) << iso;
        EXPECT_GT(delta_t_seconds(t), 69.0) << iso;
        EXPECT_EQ(tt_to_utc_iso(t).substr(0, 19), std::string(iso).substr(0, 19));
    }
}

TEST(TimeScales, TableBefore1972AndParabolaBefore1620) {
    // Rows of data/time/delta_t.csv (beginning of the year) and linear interpolation between them.
    EXPECT_NEAR(tabulated_delta_t_seconds(1900.0), -2.72, 1e-9);
    EXPECT_NEAR(tabulated_delta_t_seconds(1950.5), 0.5 * (29.15 + 29.57), 1e-9);
    EXPECT_THROW(tabulated_delta_t_seconds(1500.0), std::out_of_range);
    // delta_t_seconds uses the table before 1972 ...
    const double t1955 = utc_iso_to_j2000_seconds("1955-01-01T00:00:00Z");
    EXPECT_NEAR(delta_t_seconds(t1955), 31.07, 0.01);
    // ... and the Morrison-Stephenson parabola -20 + 32 u^2, u = (year - 1820)/100, before 1620.
    const double t1000 = (1000.0 - 2000.0) * 365.25 * ERFA_DAYSEC;  // Julian epoch 1000.0
    EXPECT_NEAR(delta_t_seconds(t1000), -20.0 + 32.0 * 8.2 * 8.2, 0.01);
    // Before 1960 there is no UTC: ISO times are UT1, TT = UT1 + Delta T (1900.0: -2.72 s).
    double d1, d2;
    eraDtf2d("UT1", 1900, 1, 1, 0, 0, 0.0, &d1, &d2);
    const double ut1900 = ((d1 - ERFA_DJ00) + d2) * ERFA_DAYSEC;
    EXPECT_NEAR(utc_iso_to_j2000_seconds("1900-01-01T00:00:00Z") - ut1900, -2.72, 0.01);
}

TEST(TimeScales, TtToUtcIsoRoundTrips) {
    for (const char* iso : {"2006-03-29T10:11:17.7Z", "2024-04-08T18:17:00.0Z", "1985-07-01T00:00:00.0Z",
                            "2016-12-31T23:59:60.5Z", "1900-01-01T00:00:00.0Z", "1969-07-20T20:17:40.0Z"})
        EXPECT_EQ(tt_to_utc_iso(utc_iso_to_j2000_seconds(iso)), iso);
    // J2000.0 = 2000-01-01T12:00:00 TT = 11:58:55.816 UTC.
    EXPECT_EQ(tt_to_utc_iso(0.0), "2000-01-01T11:58:55.8Z");
}

TEST(EarthOrientation, GreenwichFacesTheSunNearNoonUt) {
    // Where the equation of time is near zero (mid-April, mid-June, early September, late December)
    // the Sun crosses the Greenwich meridian within ~1 min of 12:00 UT1, so the sub-solar longitude
    // at 12:00 is 0 to within a quarter of a degree. Early November the equation of time is about
    // +16.4 min: the Sun culminated ~16 min before noon and is ~4.1 deg west at 12:00.
    auto subsolar_lon = [](const char* iso) {
        const double t = utc_iso_to_j2000_seconds(iso);
        const glm::dvec3 sun = apparent_geocentric_m("sun", t);
        const glm::dvec3 body = glm::conjugate(earth_orientation(t)) * sun;  // world -> ITRS
        return glm::degrees(std::atan2(body.y, body.x));
    };
    for (const char* iso :
         {"2024-04-15T12:00:00Z", "2024-06-13T12:00:00Z", "2024-09-01T12:00:00Z", "2024-12-25T12:00:00Z"})
        EXPECT_NEAR(subsolar_lon(iso), 0.0, 0.25) << iso;
    EXPECT_NEAR(subsolar_lon("2024-11-03T12:00:00Z"), -4.1, 0.2);
    // The quaternion is the transpose of ERFA's GCRS->ITRS matrix (row/column order checked).
    const double t = utc_iso_to_j2000_seconds("2024-04-08T18:17:00Z");
    const glm::dmat3 to_world = glm::mat3_cast(earth_orientation(t));
    const glm::dmat3 c2t = gcrs_to_itrs(t);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(to_world[j][i], c2t[i][j], 1e-12);
    // The ITRS pole in the world frame: precessed from the J2000 pole by ~20"/yr x 24.3 yr = 0.135 deg.
    const double tilt = glm::degrees(2.0 * std::asin(0.5 * glm::length(to_world[2] - glm::dvec3(0, 0, 1))));
    EXPECT_NEAR(tilt, 0.135, 0.01);
}

TEST(EarthOrientation, GeodeticPointsRoundTripThroughTheWorldFrame) {
    const double t = utc_iso_to_j2000_seconds("2006-03-29T10:11:00Z");
    const glm::dquat q = earth_orientation(t);
    const glm::dmat3 c2t = gcrs_to_itrs(t);
    for (const auto& [lat, lon] : {std::pair{23.15, 16.75}, std::pair{-33.9, 151.2}, std::pair{89.0, -120.0}}) {
        double xyz[3], elong, phi, h;
        ASSERT_EQ(eraGd2gc(ERFA_WGS84, glm::radians(lon), glm::radians(lat), 0.0, xyz), 0);
        const glm::dvec3 world = q * glm::dvec3(xyz[0], xyz[1], xyz[2]);
        const glm::dvec3 back = c2t * world;
        double b[3] = {back.x, back.y, back.z};
        ASSERT_EQ(eraGc2gd(ERFA_WGS84, b, &elong, &phi, &h), 0);
        EXPECT_NEAR(glm::degrees(phi), lat, 1e-9);
        EXPECT_NEAR(glm::degrees(elong), lon, 1e-9);
        EXPECT_NEAR(h, 0.0, 1e-3);
    }
}

TEST(SkyPositions, SunAgreesWithMeeus25b) {
    const SkyPosition s = sky_position("sun", tt_from_jd(2448908.5));
    EXPECT_NEAR(ra_diff_arcsec(s.ra_deg, 198.378178), 0.0, 1.0);
    EXPECT_NEAR(arcsec(s.dec_deg - -7.783871), 0.0, 1.0);
    // Meeus's R is the geometric Earth-Sun distance from his truncated VSOP87; ours the light-time
    // distance from eraEpv00: they agree to ~100 km (7e-7 AU).
    EXPECT_NEAR(s.distance_km, 0.99760775 * ERFA_DAU / 1000.0, 200.0);
}

TEST(SkyPositions, MoonAgreesWithMeeus47a) {
    const SkyPosition m = sky_position("moon", tt_from_jd(2448724.5));
    EXPECT_NEAR(ra_diff_arcsec(m.ra_deg, 134.688470), 0.0, 2.0);
    EXPECT_NEAR(arcsec(m.dec_deg - 13.768368), 0.0, 2.0);
    EXPECT_NEAR(m.distance_km, 368409.7, 1.0);
}

TEST(SkyPositions, VenusAgreesWithMeeus33a) {
    const SkyPosition v = sky_position("venus", tt_from_jd(2448976.5));
    // Meeus computes with the full VSOP87, as Cupola does (scene/planet_series).
    EXPECT_NEAR(ra_diff_arcsec(v.ra_deg, (21.0 + 4.0 / 60 + 41.454 / 3600) * 15.0), 0.0, 1.5);
    EXPECT_NEAR(arcsec(v.dec_deg - -(18.0 + 53.0 / 60 + 16.84 / 3600)), 0.0, 1.5);
    EXPECT_THROW(sky_position("vulcan", 0.0), std::invalid_argument);
    for (const auto& name : sky_body_names()) EXPECT_GT(sky_position(name, 0.0).distance_km, 3.0e5) << name;
}

TEST(SceneEphemeris, WorldPositionsArePlacedForAGeocentricViewer) {
    BodyConfig sun, earth, moon;
    sun.ephemeris = "sun", earth.ephemeris = "earth", moon.ephemeris = "moon";
    sun.id = 0, earth.id = 1, moon.id = 2;
    const double t = tt_from_jd(2453823.925261);  // 2006-03-29 greatest eclipse (NASA)
    const BodyState s = body_state(sun, t), e = body_state(earth, t), m = body_state(moon, t);
    EXPECT_EQ(m.id, 2);
    // Earth at its geometric heliocentric position, the others at Earth + apparent vector.
    EXPECT_NEAR(glm::length(e.position_m - earth_heliocentric_m(t)), 0.0, 1e-3);
    EXPECT_NEAR(glm::length(m.position_m - e.position_m - apparent_geocentric_m("moon", t)), 0.0, 1e-3);
    // So the Sun is ~20.5" of aberration (about 14 900 km at 1 AU) away from the world origin ...
    EXPECT_NEAR(glm::length(s.position_m) / 1000.0, 14900.0, 300.0);
    // ... and the rendered shadow axis (Sun -> Moon in the world frame) misses the Earth's centre
    // by exactly the eclipse code's gamma.
    const glm::dvec3 a = glm::normalize(m.position_m - s.position_m), rel = e.position_m - m.position_m;
    const double miss = glm::length(rel - glm::dot(rel, a) * a) / kEarthEquatorialRadius_m;
    EXPECT_NEAR(miss, std::abs(solar_eclipse_at(t).gamma), 1e-6);
    // The Moon keeps its near side (+X, longitude 0) to the Earth, within its libration (< 10 deg);
    // the libration itself is tested in test_body_rotation.
    const glm::dvec3 x = glm::mat3_cast(m.orientation)[0];
    EXPECT_GT(glm::dot(x, glm::normalize(e.position_m - m.position_m)), std::cos(glm::radians(10.0)));
    BodyConfig vulcan;
    vulcan.ephemeris = "vulcan";
    EXPECT_THROW(body_state(vulcan, t), std::invalid_argument);
}

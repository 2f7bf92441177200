#pragma once
// Simulation time: seconds since J2000.0 (2000-01-01T12:00:00 TT). Conversions go through ERFA
// (leap seconds, TAI, TT, calendar); no calendar arithmetic is hand-written here.
//
// UT1 (the Earth's rotation angle) = TT - ΔT, with ΔT = TT - UT1 from:
//   - 1972 onward: the leap-second table in ERFA, ΔT = 32.184 s + (TAI - UTC), i.e. UT1 is taken as
//     UTC. UTC is kept within 0.9 s of UT1 by definition, so that is the error bound (about 0.4"
//     of Earth rotation, 200 m on the equator). Beyond ERFA's leap-second horizon (eraDat's
//     "dubious year", currently 2027 on) ΔT is blended linearly over 100 years into the parabola
//     below: a rough extrapolation, since future leap seconds are unknown.
//   - 1620 to 1972: the yearly values of The Astronomical Almanac in data/time/delta_t.csv
//     (provenance in data/time/PROVENANCE.md), linearly interpolated.
//   - before 1620: the Morrison & Stephenson (2004) parabola ΔT = -20 + 32 u², u = (year - 1820)/100.
// Before 1960 (no UTC) the "UTC" of the ISO functions below is read as UT1.
#include <string>

namespace cupola {

// A two-part Julian date, ERFA's convention: JD = jd1 + jd2.
struct JulianDate {
    double jd1 = 2451545.0;
    double jd2 = 0.0;
};

// "2024-04-08T18:17:00Z" or "2024-04-08T18:17:00.5" (UTC) -> seconds since J2000 TT. Before 1960
// and from the first year ERFA's leap-second table does not vouch for, the time is taken as UT1
// (UTC stays within 0.9 s of it) and TT = UT1 + Delta T, so that the Earth turns with the time
// given and not with leap seconds nobody has announced yet.
// Throws std::invalid_argument naming the text on a malformed or impossible date.
double utc_iso_to_j2000_seconds(const std::string& iso);

// Seconds since J2000 TT -> "YYYY-MM-DDTHH:MM:SS.sZ" (UTC, tenths of a second; UT1 before 1960 and past the leap
// seconds).
std::string tt_to_utc_iso(double t_tt_s);

// ΔT = TT - UT1 in seconds at the given TT (rules above). Throws std::runtime_error if a date
// before 1972 needs data/time/delta_t.csv and the file cannot be read.
double delta_t_seconds(double t_tt_s);

// ΔT from the stored table alone (years 1620.0 to 1995.0, linear interpolation); throws
// std::out_of_range outside it. delta_t_seconds uses it before 1972; later rows are a check.
double tabulated_delta_t_seconds(double year);

// TT and UT1 of a simulation time as two-part Julian dates (what ERFA functions take).
JulianDate tt_julian_date(double t_tt_s);
JulianDate tt_to_ut1_jd(double t_tt_s);

// Julian centuries since J2000 TT.
inline double julian_centuries(double t_s) { return t_s / (36525.0 * 86400.0); }

}  // namespace cupola

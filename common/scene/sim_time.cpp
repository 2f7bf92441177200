#include "scene/sim_time.hpp"

#include <erfa.h>
#include <erfam.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "util/data_files.hpp"

namespace cupola {

namespace {

constexpr double kTtMinusTai_s = 32.184;

// Morrison & Stephenson (2004) long-term parabola.
double parabola_delta_t(double year) {
    const double u = (year - 1820.0) / 100.0;
    return -20.0 + 32.0 * u * u;
}

// data/time/delta_t.csv, read once: (year, ΔT) rows in increasing year.
const std::vector<std::pair<double, double>>& delta_t_table() {
    static std::vector<std::pair<double, double>> rows;
    static std::once_flag once;
    std::call_once(once, [] {
        const std::string table = data_file("time/delta_t.csv");
        std::ifstream in(table);
        if (!in) throw std::runtime_error(table + ": cannot open the Delta T table");
        std::string line;
        while (std::getline(in, line)) {
            double y, dt;
            if (line.empty() || line[0] == '#' || std::sscanf(line.c_str(), "%lf,%lf", &y, &dt) != 2) continue;
            if (!rows.empty() && y <= rows.back().first)
                throw std::runtime_error(table + ": years must increase (" + line + ")");
            rows.emplace_back(y, dt);
        }
        if (rows.size() < 2) throw std::runtime_error(table + ": no data rows");
    });
    return rows;
}

// First year for which ERFA's leap-second table no longer vouches for TAI-UTC.
int leap_second_horizon_year() {
    static const int year = [] {
        double dat;
        int y = 2000;
        while (y < 2200 && eraDat(y, 1, 1, 0.0, &dat) == 0) ++y;
        return y;
    }();
    return year;
}

// 32.184 s + TAI-UTC on the (TT) calendar date of t; the ~1 min difference between TT and UTC
// only matters in the minute before a leap second.
double leap_second_delta_t(double t_tt_s) {
    int iy, im, id;
    double fd, dat;
    eraJd2cal(ERFA_DJ00, t_tt_s / ERFA_DAYSEC, &iy, &im, &id, &fd);
    eraDat(iy, im, id, fd, &dat);
    return kTtMinusTai_s + dat;
}

double decimal_year(double t_tt_s) { return eraEpj(ERFA_DJ00, t_tt_s / ERFA_DAYSEC); }

}  // namespace

double tabulated_delta_t_seconds(double year) {
    const auto& rows = delta_t_table();
    if (!(year >= rows.front().first && year <= rows.back().first))
        throw std::out_of_range("year " + std::to_string(year) + " is outside the Delta T table (1620-1995)");
    size_t i = 1;
    while (i + 1 < rows.size() && rows[i].first < year) ++i;
    const auto& [y0, d0] = rows[i - 1];
    const auto& [y1, d1] = rows[i];
    return d0 + (d1 - d0) * (year - y0) / (y1 - y0);
}

double delta_t_seconds(double t_tt_s) {
    const double year = decimal_year(t_tt_s);
    if (year < 1620.0) return parabola_delta_t(year);
    if (year < 1972.0) return tabulated_delta_t_seconds(year);
    const double horizon = leap_second_horizon_year();
    if (year < horizon) return leap_second_delta_t(t_tt_s);
    // Past the leap-second table: blend from its last value into the long-term parabola.
    const double last = leap_second_delta_t((horizon - 2000.0) * 365.25 * ERFA_DAYSEC - 1.0);
    const double f = (year - horizon) / 100.0;
    return f >= 1.0 ? parabola_delta_t(year) : last + f * (parabola_delta_t(horizon + 100.0) - last);
}

JulianDate tt_julian_date(double t_tt_s) { return {ERFA_DJ00, t_tt_s / ERFA_DAYSEC}; }

JulianDate tt_to_ut1_jd(double t_tt_s) { return {ERFA_DJ00, (t_tt_s - delta_t_seconds(t_tt_s)) / ERFA_DAYSEC}; }

double utc_iso_to_j2000_seconds(const std::string& iso) {
    int y, mo, d, h, mi;
    double s;
    char tail[8] = {};
    int n = std::sscanf(iso.c_str(), "%d-%d-%dT%d:%d:%lf%7s", &y, &mo, &d, &h, &mi, &s, tail);
    if (n < 6 || (n == 7 && std::string(tail) != "Z"))
        throw std::invalid_argument("\"" + iso + "\" is not an ISO 8601 UTC time like 2024-04-08T18:17:00Z");
    double u1, u2, a1, a2, t1, t2;
    if (eraDtf2d("UTC", y, mo, d, h, mi, s, &u1, &u2) < 0)
        throw std::invalid_argument("\"" + iso + "\" is not a valid UTC date and time");
    if (y < 1960 || y >= leap_second_horizon_year()) {
        // No UTC yet, or past the leap seconds anyone knows (UTC will stay within 0.9 s of UT1):
        // the time is UT1, and TT = UT1 + ΔT (ΔT evaluated at TT, one iteration).
        const double ut1 = ((u1 - ERFA_DJ00) + u2) * ERFA_DAYSEC;
        return ut1 + delta_t_seconds(ut1 + delta_t_seconds(ut1));
    }
    if (eraUtctai(u1, u2, &a1, &a2) < 0 || eraTaitt(a1, a2, &t1, &t2) != 0)
        throw std::invalid_argument("\"" + iso + "\" cannot be converted to TT");
    return ((t1 - ERFA_DJ00) + t2) * ERFA_DAYSEC;
}

std::string tt_to_utc_iso(double t_tt_s) {
    const JulianDate tt = tt_julian_date(t_tt_s);
    double u1, u2;
    const char* scale = "UTC";
    if (decimal_year(t_tt_s) < 1960.0 || decimal_year(t_tt_s) >= leap_second_horizon_year()) {
        const JulianDate ut1 = tt_to_ut1_jd(t_tt_s);
        u1 = ut1.jd1, u2 = ut1.jd2, scale = "UT1";
    } else {
        double a1, a2;
        if (eraTttai(tt.jd1, tt.jd2, &a1, &a2) != 0 || eraTaiutc(a1, a2, &u1, &u2) < 0)
            throw std::invalid_argument("TT " + std::to_string(t_tt_s) + " s cannot be converted to UTC");
    }
    int y, mo, d, hmsf[4];
    if (eraD2dtf(scale, 1, u1, u2, &y, &mo, &d, hmsf) < 0)
        throw std::invalid_argument("TT " + std::to_string(t_tt_s) + " s is outside the calendar");
    char buf[48];
    std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%01dZ", y, mo, d, hmsf[0], hmsf[1], hmsf[2], hmsf[3]);
    return buf;
}

}  // namespace cupola

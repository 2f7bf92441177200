#include "scene/sim_time.hpp"

#include <erfa.h>
#include <erfam.h>

#include <cstdio>
#include <stdexcept>

namespace cupola {

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
    if (eraUtctai(u1, u2, &a1, &a2) < 0 || eraTaitt(a1, a2, &t1, &t2) != 0)
        throw std::invalid_argument("\"" + iso + "\" cannot be converted to TT");
    return ((t1 - ERFA_DJ00) + t2) * ERFA_DAYSEC;
}

}  // namespace cupola

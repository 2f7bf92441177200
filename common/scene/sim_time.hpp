#pragma once
// Simulation time: seconds since J2000.0 (2000-01-01T12:00:00 TT). Conversions from UTC go
// through ERFA (leap seconds, TAI, TT); no time arithmetic is hand-written here.
#include <string>

namespace cupola {

// "2024-04-08T18:17:00Z" or "2024-04-08T18:17:00.5" (UTC) -> seconds since J2000 TT.
// Throws std::invalid_argument naming the text on a malformed or impossible date.
double utc_iso_to_j2000_seconds(const std::string& iso);

// Julian centuries since J2000 TT.
inline double julian_centuries(double t_s) { return t_s / (36525.0 * 86400.0); }

}  // namespace cupola

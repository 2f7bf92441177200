#pragma once
// Solar and lunar eclipse geometry from the apparent geocentric Sun and Moon of
// scene/sky_positions (the same vectors the scene renders with). Method, sources and measured
// agreement with NASA's published eclipse data: docs/ephemeris-accuracy.md.
//
// Solar: the Moon's shadow axis is the line from the Sun's centre through the Moon's centre. It is
// intersected with the WGS84 ellipsoid (in ITRS: z scaled by a/b, then a sphere of radius a) and
// the point converted to geodetic latitude and longitude (eraGc2gd). Greatest eclipse is NASA's:
// the instant the axis passes closest to the Earth's centre; gamma is that distance in Earth
// equatorial radii, positive when the axis passes north of the centre.
//
// Lunar: the Earth's shadow axis is the anti-Sun direction from the geocentre. Greatest eclipse is
// the instant the Moon's centre is closest to it. Shadow radii follow Danjon's rule (Earth's radius
// enlarged by 1/85, as NASA's Five Millennium Canon and the Connaissance des Temps do):
//   penumbra Rp = 1.01 pi_m + pi_s + s_s,   umbra Ru = 1.01 pi_m + pi_s - s_s
// with pi_m, pi_s the equatorial horizontal parallaxes of the Moon and Sun and s_s the Sun's
// geocentric semi-diameter (https://eclipse.gsfc.nasa.gov/LEcat5/shadow.html).
//
// Small angles are computed as 2 asin(|u1 - u2| / 2) of unit vectors, never acos(dot).
#include <string>

namespace cupola {

constexpr double kSunRadius_m = 6.96e8;
constexpr double kEarthEquatorialRadius_m = 6378137.0;                  // WGS84 a
constexpr double kEarthFlattening = 1.0 / 298.257223563;                // WGS84 f
constexpr double kMoonRadius_m = 0.2725076 * kEarthEquatorialRadius_m;  // IAU k (NASA's k1): 1737.4 km

struct SolarEclipseAt {
    // At (lat_deg, lon_deg): "total" (inside the umbra, before its apex), "annular" (inside the
    // antumbra, beyond the apex), "partial" (inside the penumbra) or "none".
    std::string type = "none";
    // Geodetic WGS84 point where the shadow axis meets the Earth (central == true); if the axis
    // misses, the surface point closest to the axis.
    double lat_deg = 0.0, lon_deg = 0.0;
    bool central = false;
    // Fraction of the Sun's diameter covered, seen from that point (topocentric radii and
    // separation); inside the umbra or antumbra the ratio of apparent diameters Moon/Sun.
    double magnitude = 0.0;
    double gamma = 0.0;  // axis distance from the Earth's centre, equatorial radii, + north
};

SolarEclipseAt solar_eclipse_at(double t_tt_s);

struct EclipseEvent {
    double peak_tt_s = 0.0;  // greatest eclipse, seconds since J2000 TT
    // solar: "total", "annular" (axis meets the Earth) or "partial"; lunar: "total", "partial", "penumbral"
    std::string type;
    // solar: the axis point (or the point closest to the axis), geodetic; lunar: the sub-lunar
    // point (the Moon's geocentric direction in ITRS), geocentric latitude.
    double lat_deg = 0.0, lon_deg = 0.0;
    // solar: as SolarEclipseAt::magnitude at that point; lunar: umbral magnitude (fraction of the
    // Moon's diameter inside the umbra), or the penumbral magnitude for a penumbral eclipse.
    double magnitude = 0.0;
    double gamma = 0.0;                // equatorial radii, + north (lunar: Moon north of the axis)
    double penumbral_magnitude = 0.0;  // lunar only
};

// The first eclipse whose greatest eclipse is after t (searched up to two years ahead; throws
// std::runtime_error if none is found, which does not happen with real ephemerides).
EclipseEvent next_solar_eclipse(double t_tt_s);
EclipseEvent next_lunar_eclipse(double t_tt_s);

}  // namespace cupola

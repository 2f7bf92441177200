#!/usr/bin/env python3
"""Write the independent ephemeris Cupola's positions are tested against (tests/test_ephemeris_reference.cpp).

Usage: python3 tools/make_ephemeris_reference.py data/ephemeris/pyephem_reference.csv \
                                                 data/ephemeris/pyephem_orientation.csv \
                                                 data/ephemeris/pyephem_topocentric.csv \
                                                 data/ephemeris/pyephem_galilean.csv

Source: PyEphem (Debian package python3-ephem, 4.1.4), whose libastro computes the planets from its
own truncated VSOP87 code, the Moon from its own ELP 2000-82 code and Pluto from its own series,
none of which shares code with ERFA or libnova (the two libraries Cupola uses).
For each body, 40 instants spread over 1900-2100 (a fixed random sequence, seed 18) give PyEphem's
astrometric geocentric place: light-time corrected, no aberration, J2000 equator and equinox.
The instant is given in TT (Julian date); PyEphem takes UT, so the date handed to it is TT minus
PyEphem's own Delta T, iterated: both sides then compute at the same TT instant.
Output columns: body,tt_jd,ra_deg,dec_deg (deterministic for a given PyEphem version).

The second file holds orientations on 10 instants each (seed 53), geocentric: the Moon's libration
in longitude and latitude (libastro's own lunar libration code, after Meeus 1998 ch. 53) and
Jupiter's System II central meridian (libastro, after Meeus 1998 ch. 43).
Columns: body,tt_jd,quantity,value_deg.

The third holds the Moon seen from three places on the ground on 12 instants each (seed 71,
1975-2060 UTC, taken as UT): PyEphem's apparent topocentric place (ra, dec; no refraction) and its
apparent geocentric place (g_ra, g_dec), both for the equator and equinox of date. Their difference
is the topocentric parallax the test checks.
Columns: lat_deg,lon_deg,alt_m,utc,topo_ra_deg,topo_dec_deg,geo_ra_deg,geo_dec_deg.

The fourth holds the Galilean moons' places relative to Jupiter's, on 30 instants each (seed 29,
1950-2050 TT): libastro's own theory of the moons (after Meeus 1998 ch. 44), as its x and y (the
offset on the sky in Jupiter's equatorial radii, x east, y south) times Jupiter's angular radius:
east_arcsec and north_arcsec. (PyEphem's own ra of a moon is Jupiter's plus x times the radius,
without the 1 / cos dec that turns an offset east into one in right ascension, so it is not used.)
Columns: moon,tt_jd,east_arcsec,north_arcsec.
"""
import datetime
import math
import random
import sys

import ephem

BODIES = [("sun", ephem.Sun), ("moon", ephem.Moon), ("mercury", ephem.Mercury), ("venus", ephem.Venus),
          ("mars", ephem.Mars), ("jupiter", ephem.Jupiter), ("saturn", ephem.Saturn), ("uranus", ephem.Uranus),
          ("neptune", ephem.Neptune), ("pluto", ephem.Pluto)]
DUBLIN_JD = 2415020.0  # PyEphem dates count days from 1899 Dec 31 12:00


def ut_date_for_tt(tt_jd):
    ut = tt_jd - DUBLIN_JD
    for _ in range(4):
        ut = tt_jd - DUBLIN_JD - ephem.delta_t(ephem.Date(ut)) / 86400.0
    return ephem.Date(ut)


def orientation_rows():
    rng = random.Random(53)
    j1900, j2100 = 2415020.5, 2488069.5
    rows = ["body,tt_jd,quantity,value_deg"]
    for _ in range(10):
        tt_jd = round(j1900 + (j2100 - j1900) * rng.random(), 6)
        m = ephem.Moon(ut_date_for_tt(tt_jd))
        rows.append(f"moon,{tt_jd:.6f},libration_long,{math.degrees(m.libration_long):.6f}")
        rows.append(f"moon,{tt_jd:.6f},libration_lat,{math.degrees(m.libration_lat):.6f}")
    for _ in range(10):
        tt_jd = round(j1900 + (j2100 - j1900) * rng.random(), 6)
        j = ephem.Jupiter(ut_date_for_tt(tt_jd))
        rows.append(f"jupiter,{tt_jd:.6f},cml_system_ii,{math.degrees(j.cmlII):.6f}")
    return rows


SITES = [(50.927, 11.586, 150.0), (-0.18, -78.47, 2850.0), (-33.87, 151.21, 50.0)]


def topocentric_rows():
    rng = random.Random(71)
    first, last = ephem.Date("1975/01/01"), ephem.Date("2060/01/01")
    rows = ["lat_deg,lon_deg,alt_m,utc,topo_ra_deg,topo_dec_deg,geo_ra_deg,geo_dec_deg"]
    for lat, lon, alt in SITES:
        for _ in range(12):
            day = ephem.Date(round(first + (last - first) * rng.random()) + rng.randrange(86400) / 86400.0)
            when = (day.datetime() + datetime.timedelta(microseconds=500000)).replace(microsecond=0)
            date = ephem.Date(when)
            o = ephem.Observer()
            o.lat, o.lon, o.elevation, o.pressure, o.date = str(lat), str(lon), alt, 0.0, date
            m = ephem.Moon(o)
            utc = when.strftime("%Y-%m-%dT%H:%M:%SZ")
            rows.append(f"{lat},{lon},{alt},{utc},{math.degrees(m.ra):.9f},{math.degrees(m.dec):.9f},"
                        f"{math.degrees(m.g_ra):.9f},{math.degrees(m.g_dec):.9f}")
    return rows


GALILEAN = [("io", ephem.Io), ("europa", ephem.Europa), ("ganymede", ephem.Ganymede),
            ("callisto", ephem.Callisto)]


def galilean_rows():
    rng = random.Random(29)
    j1950, j2050 = 2433282.5, 2469807.5
    rows = ["moon,tt_jd,east_arcsec,north_arcsec"]
    for name, make in GALILEAN:
        for _ in range(30):
            tt_jd = round(j1950 + (j2050 - j1950) * rng.random(), 6)
            date = ut_date_for_tt(tt_jd)
            m, j = make(date), ephem.Jupiter(date)
            radius_arcsec = math.degrees(j.radius) * 3600.0
            rows.append(f"{name},{tt_jd:.6f},{m.x * radius_arcsec:.4f},{-m.y * radius_arcsec:.4f}")
    return rows


def main():
    if len(sys.argv) != 5:
        raise SystemExit(__doc__)
    rng = random.Random(18)
    j1900, j2100 = 2415020.5, 2488069.5
    rows = ["body,tt_jd,ra_deg,dec_deg"]
    for name, make in BODIES:
        for _ in range(40):
            tt_jd = round(j1900 + (j2100 - j1900) * rng.random(), 6)
            b = make(ut_date_for_tt(tt_jd))
            rows.append(f"{name},{tt_jd:.6f},{math.degrees(b.a_ra):.9f},{math.degrees(b.a_dec):.9f}")
    with open(sys.argv[1], "w") as f:
        f.write("\n".join(rows) + "\n")
    with open(sys.argv[2], "w") as f:
        f.write("\n".join(orientation_rows()) + "\n")
    with open(sys.argv[3], "w") as f:
        f.write("\n".join(topocentric_rows()) + "\n")
    with open(sys.argv[4], "w") as f:
        f.write("\n".join(galilean_rows()) + "\n")


if __name__ == "__main__":
    main()

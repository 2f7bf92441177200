#!/usr/bin/env python3
"""Fit the mean orbital elements of Titan that common/scene/satellite_orbits.cpp holds.

Usage: /usr/bin/python3 tools/fit_titan_elements.py [data/ephemeris/pyephem_titan.csv]

Source: PyEphem (Debian package python3-ephem, 4.1.4). From 1999 to 2040 its libastro takes the
moons of Saturn from the Bureau des Longitudes' tabulated ephemerides (Chebyshev-like series fitted
to the TASS 1.7 theory of Vienne & Duriez 1995): Titan's offset from Saturn on the sky, x east,
y north, z away from the Earth, light-time corrected, in Saturn radii of 0.0004014253 AU. Outside
those years libastro falls back to a circular-orbit model that ignores the tilt of Saturn's pole
on the sky (Titan up to 7 degrees off its orbital plane): it is not used.

The offsets at 8 809 instants over 1999-2039 (every 1.7 days, TT) are turned into vectors in the
ICRS (east, north and the line of sight at Saturn's astrometric J2000 place) and fitted, by
Gauss-Newton least squares, with the model satellite_orbits.cpp evaluates: a precessing ellipse on
a Laplace plane whose pole is fixed in the ICRS, the periapsis advancing and the node regressing
uniformly. Eleven parameters: a, e, i, the argument of periapsis, the mean anomaly and the node at
J2000 TT, the mean longitude's rate, the periapsis' and the node's periods, the plane's pole.
The model is evaluated at the instant the light left Titan (Saturn's light time earlier), as the
C++ does. The fit prints the table row and its residuals.

With an output path, it also writes the reference the test compares with: 40 instants over
1999-2039 (seed 61, not the fit's grid) as tt_jd,east_arcsec,north_arcsec (Titan's offset from
Saturn on the sky, J2000 axes).
"""
import math
import random
import sys

import ephem
import numpy as np

DUBLIN_JD = 2415020.0
J2000 = 2451545.0
SATURN_RADIUS_KM = 0.0004014253 * 149597870.7  # libastro's SATRAU
LIGHT_AU_DAYS = 499.004783836 / 86400.0
FIRST_JD, LAST_JD = 2451180.5, 2466154.5  # 1999 Jan 2 .. 2040 Jan 1: its tables (the last breaks in 2040 Feb)


def ut_date_for_tt(tt_jd):
    ut = tt_jd - DUBLIN_JD
    for _ in range(4):
        ut = tt_jd - DUBLIN_JD - ephem.delta_t(ephem.Date(ut)) / 86400.0
    return ephem.Date(ut)


def sky_axes(ra, dec):
    los = np.array([math.cos(dec) * math.cos(ra), math.cos(dec) * math.sin(ra), math.sin(dec)])
    east = np.array([-math.sin(ra), math.cos(ra), 0.0])
    return los, east, np.cross(los, east)


def observe(tt_jd):
    """Titan's ICRS offset from Saturn (km), the emission instant (days from J2000 TT), Saturn's place."""
    date = ut_date_for_tt(tt_jd)
    titan, saturn = ephem.Titan(), ephem.Saturn()
    titan.compute(date, epoch="2000")
    saturn.compute(date, epoch="2000")
    los, east, north = sky_axes(float(saturn.a_ra), float(saturn.a_dec))
    # libastro: x east, y south, z toward the Earth (its BDL reader flips y and z).
    offset = (titan.x * east - titan.y * north - titan.z * los) * SATURN_RADIUS_KM
    t_emit = tt_jd - J2000 - saturn.earth_distance * LIGHT_AU_DAYS
    return offset, t_emit, (los, east, north), titan


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def model(p, t):
    """satellite_orbits.cpp's ellipse: p = a_km, e, i, omega0, M0, node0 (deg), n (deg/day),
    periapsis and node periods (years), pole ra, dec (deg); t in days from J2000 TT."""
    a, e, inc, w0, m0, node0, n, pw, pn, pra, pdec = p
    w_rate, node_rate = 360.0 / (pw * 365.25), -360.0 / (pn * 365.25)
    w = math.radians(w0 + w_rate * t)
    node = math.radians(node0 + node_rate * t)
    m = math.radians(m0 + (n - w_rate - node_rate) * t)
    ecc = m
    for _ in range(8):
        ecc -= (ecc - e * math.sin(ecc) - m) / (1.0 - e * math.cos(ecc))
    in_orbit = np.array([a * (math.cos(ecc) - e), a * math.sqrt(1.0 - e * e) * math.sin(ecc), 0.0])
    to_laplace = rot_z(node) @ rot_x(math.radians(inc)) @ rot_z(w)
    to_icrs = rot_z(math.radians(pra + 90.0)) @ rot_x(math.radians(90.0 - pdec))
    return to_icrs @ (to_laplace @ in_orbit)


def from_longitudes(q):
    """The fit's parameters hold the mean longitude, the periapsis' longitude and the node in place
    of the mean anomaly, the argument of periapsis and the node (better conditioned: e and i are
    small); this gives the model's."""
    p = np.array(q, dtype=float)
    p[3], p[4] = q[4] - q[5], q[3] - q[4]
    return p


def to_longitudes(p):
    q = np.array(p, dtype=float)
    q[3], q[4] = p[3] + p[4] + p[5], p[3] + p[5]
    return q


def residuals(q, times, offsets):
    p = from_longitudes(q)
    return np.concatenate([model(p, t) - o for t, o in zip(times, offsets)])


def fit(times, offsets, p, free):
    """Levenberg-Marquardt on the first `free` parameters (the rest held): Gauss-Newton steps,
    damped until each one lowers the residual."""
    p = np.array(p, dtype=float)
    steps = np.array([1.0, 1e-6, 1e-4, 1e-3, 1e-3, 1e-3, 1e-9, 1.0, 1.0, 1e-4, 1e-4])
    damping = 1e-3
    r = residuals(p, times, offsets)
    for _ in range(40):
        jac = np.zeros((r.size, p.size))
        for k in range(free):
            q = p.copy()
            q[k] += steps[k]
            jac[:, k] = (residuals(q, times, offsets) - r) / steps[k]
        normal = jac.T @ jac + np.diag([0.0] * free + [1.0] * (p.size - free))
        while damping < 1e12:
            trial = p + np.linalg.lstsq(normal + damping * np.diag(np.diag(normal)), -jac.T @ r, rcond=None)[0]
            trial[1] = min(max(trial[1], 0.0), 0.5)
            r_trial = residuals(trial, times, offsets)
            if r_trial @ r_trial < r @ r:
                p, r, damping = trial, r_trial, damping / 10.0
                break
            damping *= 10.0
    return p


def reference_rows():
    rng = random.Random(61)
    rows = ["tt_jd,east_arcsec,north_arcsec"]
    for _ in range(40):
        tt_jd = round(FIRST_JD + (LAST_JD - FIRST_JD) * rng.random(), 6)
        _, _, _, titan = observe(tt_jd)
        saturn = ephem.Saturn()
        saturn.compute(ut_date_for_tt(tt_jd), epoch="2000")
        radius_arcsec = SATURN_RADIUS_KM / (saturn.earth_distance * 149597870.7) * 206264.806247
        rows.append(f"{tt_jd:.6f},{titan.x * radius_arcsec:.4f},{-titan.y * radius_arcsec:.4f}")
    return rows


def main():
    grid = np.arange(FIRST_JD, LAST_JD, 1.7)
    obs = [observe(jd) for jd in grid]
    times = [o[1] for o in obs]
    offsets = [o[0] for o in obs]
    # Start: Jacobson (1998) appendix A's orbit (e 0.0288, i 0.57 deg, its Laplacian pole) and
    # Titan's synchronous rotation (IAU), which puts its mean longitude near 7 deg at J2000.
    start = [1221870.0, 0.0288, 0.57, 349.0, 164.0, 214.5, 22.5769768, 703.0, 1216.0, 40.581056, 83.225166]
    p = from_longitudes(fit(times, offsets, to_longitudes(start), 9))
    err = np.linalg.norm(residuals(to_longitudes(p), times, offsets).reshape(-1, 3), axis=1)
    names = ["a_km", "e", "i_deg", "omega_deg", "M_deg", "node_deg", "n_deg_per_day", "P_periapsis_yr",
             "P_node_yr", "pole_ra_deg", "pole_dec_deg"]
    for name, value in zip(names, p):
        print(f"{name:>15} {value:.9g}")
    print(f"residual: rms {math.sqrt(np.mean(err ** 2)):.0f} km, worst {err.max():.0f} km over {len(grid)} instants")
    if len(sys.argv) > 1:
        with open(sys.argv[1], "w") as f:
            f.write("\n".join(reference_rows()) + "\n")


if __name__ == "__main__":
    main()

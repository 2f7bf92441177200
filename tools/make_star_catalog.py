#!/usr/bin/env python3
"""Convert KStars' stars.dat (Debian package kstars-data) into Cupola's compact star catalogue.

Usage: python3 tools/make_star_catalog.py /usr/share/kstars/stars.dat data/stars/bright_stars.csv [--vmax 6.5]

stars.dat is fixed-width ASCII derived from Hipparcos/Tycho (CDS I/239), J2000 positions:
  [0:9]   RA  hhmmss.ss        [10:19] Dec sddmmss.s
  [20:29] pmRA [29:38] pmDec [38:45] parallax (unused here)
  [45:51] V magnitude          [51:56] B-V colour index       [56:58] spectral type
  after the first ", ": Bayer/Flamsteed (genetive) designation, then ", " and a common name.
Output columns: ra_deg,dec_deg,vmag,bv,name  (name may be empty; commas never occur in it).
The output is deterministic: stars keep the order of the input file (brightest first).
"""
import argparse
import sys


def parse_line(line, lineno, path):
    try:
        ra_s, dec_s = line[0:9], line[10:19]
        hh, mm, ss = int(ra_s[0:2]), int(ra_s[2:4]), float(ra_s[4:9])
        sign = -1.0 if dec_s[0] == '-' else 1.0
        dd, dm, ds = int(dec_s[1:3]), int(dec_s[3:5]), float(dec_s[5:9])
        vmag = float(line[45:51])
        bv = float(line[51:56])
    except (ValueError, IndexError) as e:
        raise SystemExit(f"{path}:{lineno}: cannot parse star line ({e}): {line.rstrip()}")
    # The source has a few rounded seconds of exactly 60.00 (e.g. kap Cas, line 629); they are kept.
    if not (0 <= hh < 24 and 0 <= mm < 60 and 0 <= ss <= 60 and dd <= 90 and dm < 60 and 0 <= ds <= 60):
        raise SystemExit(f"{path}:{lineno}: coordinates out of range: {line.rstrip()}")
    ra_deg = 15.0 * (hh + mm / 60.0 + ss / 3600.0)
    dec_deg = sign * (dd + dm / 60.0 + ds / 3600.0)
    name = ''
    if ', ' in line:
        parts = [p.strip() for p in line.rstrip('\n').split(',')[1:]]
        parts = [p for p in parts if p]
        # Prefer the common name, else the genetive designation.
        if parts:
            name = parts[-1]
    return ra_deg, dec_deg, vmag, bv, name.replace(',', ' ')


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('stars_dat')
    ap.add_argument('output_csv')
    ap.add_argument('--vmax', type=float, default=6.5)
    a = ap.parse_args()
    rows = []
    with open(a.stars_dat, encoding='latin-1') as f:
        for lineno, line in enumerate(f, 1):
            if line.startswith('#') or not line.strip():
                continue
            ra, dec, v, bv, name = parse_line(line, lineno, a.stars_dat)
            if v <= a.vmax:
                rows.append((ra, dec, v, bv, name))
    with open(a.output_csv, 'w', encoding='utf-8', newline='\n') as out:
        out.write(f'# Cupola bright-star catalogue: {len(rows)} stars with V <= {a.vmax}, J2000 (ICRS) positions.\n')
        out.write('# Derived from KStars stars.dat (Hipparcos/Tycho, CDS I/239); see PROVENANCE.md.\n')
        out.write('ra_deg,dec_deg,vmag,bv,name\n')
        for ra, dec, v, bv, name in rows:
            out.write(f'{ra:.6f},{dec:.6f},{v:.2f},{bv:.2f},{name}\n')
    print(f'wrote {len(rows)} stars to {a.output_csv}', file=sys.stderr)


if __name__ == '__main__':
    main()

#!/usr/bin/env python3
"""Convert d3-celestial's constellation data into Cupola's compact constellation file.

Usage:
  python3 tools/convert_constellations.py --source DIR --out data/sky/constellations.json \
      [--boundaries-out FILE] [--tarball d3-celestial-X.Y.Z.tgz]

DIR is the `data/` folder of the npm package `d3-celestial` (BSD-3-Clause, Olaf Frohn); the files read
are constellations.lines.json, constellations.json and constellations.bounds.json (GeoJSON
FeatureCollections). The package's package.json and LICENSE are read from DIR/.. for the provenance
block (name, version, licence, copyright line). Standard library only.

Coordinate convention (checked at run time against Betelgeuse, Rigel and Vega): d3-celestial stores
J2000 right ascension as a geographic longitude in [-180, 180] with the SAME sense as RA (east
positive, no sign flip): lon = RA for RA < 180 deg, lon = RA - 360 for RA >= 180 deg; latitude is the
declination. So RA_deg = lon if lon >= 0 else lon + 360. Output RA is in [0, 360), rounded to 4 decimals.

d3-celestial has two features with id "Ser" (Serpens Caput and Serpens Cauda) in each file. They are
merged into one "Ser" entry (88 in all): lines and boundary polygons are concatenated, the name is the
Latin name "Serpens", label_ra_deg/label_dec_deg is the first (Caput) label, and "labels" lists both.
Every entry has "labels" (one item for the other 87).

Output (deterministic; no timestamps): a JSON object
  provenance, frame, constellations[{id, name, rank, label_ra_deg, label_dec_deg, labels[{text, ra_deg,
  dec_deg}], lines[[[ra, dec], ...], ...]}], boundaries[{id, polygons[[[ra, dec], ...], ...]}]
with one constellation / boundary per line. With --boundaries-out, "boundaries" goes to that file
instead (with the same provenance and frame) and the main file has no "boundaries" key.
"""
import argparse
import hashlib
import json
import math
import os
import sys

LINES_FILE = "constellations.lines.json"
NAMES_FILE = "constellations.json"
BOUNDS_FILE = "constellations.bounds.json"
FRAME = "ICRS/J2000 equatorial, right ascension and declination in degrees, RA in [0,360)"
EXPECTED_COUNT = 88
DECIMALS = 4

# Known J2000 positions used to verify the longitude convention: (constellation, name, RA deg, Dec deg).
# Vega (RA > 180) distinguishes "lon = RA - 360" from "lon = -RA".
CHECK_STARS = [
    ("Ori", "Betelgeuse", 88.7929, 7.4071),
    ("Ori", "Rigel", 78.6342, -8.2016),
    ("Lyr", "Vega", 279.2347, 38.7837),
]
CHECK_TOLERANCE_DEG = 0.02


class InputError(Exception):
    pass


def fail(file, where, what):
    raise InputError(f"{file}: {where}: {what}")


def sha256_of(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 16), b""):
            h.update(chunk)
    return h.hexdigest()


def load_json(path):
    name = os.path.basename(path)
    try:
        with open(path, "r", encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise InputError(f"{name}: cannot read {path}: {e.strerror}")
    except json.JSONDecodeError as e:
        raise InputError(f"{name}: JSON syntax error at line {e.lineno} column {e.colno}: {e.msg}")


def features_of(doc, file):
    if not isinstance(doc, dict) or doc.get("type") != "FeatureCollection":
        fail(file, "(top level)", 'expected a GeoJSON object with "type": "FeatureCollection"')
    feats = doc.get("features")
    if not isinstance(feats, list):
        fail(file, "features", "expected an array of features")
    for i, f in enumerate(feats):
        where = f"features[{i}]"
        if not isinstance(f, dict):
            fail(file, where, "expected an object")
        fid = f.get("id")
        if not isinstance(fid, str) or not (2 <= len(fid) <= 4) or not fid.isalpha():
            fail(file, where + ".id", f"expected a 3-letter IAU abbreviation, got {fid!r}")
        if not isinstance(f.get("geometry"), dict):
            fail(file, f"{where} (id {fid!r}).geometry", "missing or not an object")
    return feats


def geometry(f, i, file, gtype):
    g = f["geometry"]
    where = f"features[{i}] (id {f['id']!r}).geometry"
    if g.get("type") != gtype:
        fail(file, where + ".type", f"expected {gtype!r}, got {g.get('type')!r}")
    if "coordinates" not in g:
        fail(file, where + ".coordinates", "missing")
    return g["coordinates"], where + ".coordinates"


def is_number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def convert_point(p, file, where):
    """GeoJSON [lon, lat] (degrees, lon in [-180,180]) -> [ra, dec] rounded, ra in [0,360)."""
    if not isinstance(p, list) or len(p) != 2 or not all(is_number(v) for v in p):
        fail(file, where, f"expected a [lon, lat] pair of finite numbers, got {json.dumps(p)[:80]}")
    lon, lat = float(p[0]), float(p[1])
    if not -180.0 <= lon <= 180.0:
        fail(file, where, f"longitude {lon} outside [-180, 180]")
    if not -90.0 <= lat <= 90.0:
        fail(file, where, f"latitude {lat} outside [-90, 90]")
    ra = lon if lon >= 0.0 else lon + 360.0
    ra = round(ra, DECIMALS)
    if ra >= 360.0:
        ra -= 360.0
    dec = round(lat, DECIMALS)
    return [ra + 0.0, dec + 0.0]  # + 0.0 turns -0.0 into 0.0


def convert_polyline(coords, file, where, min_points):
    if not isinstance(coords, list):
        fail(file, where, "expected an array of [lon, lat] points")
    if len(coords) < min_points:
        fail(file, where, f"has {len(coords)} point(s), at least {min_points} required")
    return [convert_point(p, file, f"{where}[{k}]") for k, p in enumerate(coords)]


def read_lines(path):
    file = os.path.basename(path)
    out = {}
    for i, f in enumerate(features_of(load_json(path), file)):
        coords, where = geometry(f, i, file, "MultiLineString")
        if not isinstance(coords, list) or not coords:
            fail(file, where, "expected a non-empty array of lines")
        lines = [convert_polyline(line, file, f"{where}[{j}]", 2) for j, line in enumerate(coords)]
        out.setdefault(f["id"], []).extend(lines)
    return out


def read_bounds(path):
    file = os.path.basename(path)
    out = {}
    for i, f in enumerate(features_of(load_json(path), file)):
        coords, where = geometry(f, i, file, "Polygon")
        if not isinstance(coords, list) or len(coords) != 1:
            fail(file, where, "expected exactly one (outer) ring; holes are not supported")
        ring = convert_polyline(coords[0], file, f"{where}[0]", 4)
        if ring[0] != ring[-1]:
            fail(file, f"{where}[0]", "ring is not closed (first point != last point)")
        out.setdefault(f["id"], []).append(ring)
    return out


def read_names(path):
    file = os.path.basename(path)
    out = {}
    for i, f in enumerate(features_of(load_json(path), file)):
        fid = f["id"]
        where = f"features[{i}] (id {fid!r}).properties"
        props = f.get("properties")
        if not isinstance(props, dict):
            fail(file, where, "missing or not an object")
        for key in ("name", "la"):
            if not isinstance(props.get(key), str) or not props[key].strip():
                fail(file, f"{where}.{key}", f"expected a non-empty string, got {props.get(key)!r}")
        try:
            rank = int(props.get("rank"))
        except (TypeError, ValueError):
            rank = None
        if rank not in (1, 2, 3):
            fail(file, f"{where}.rank", f"expected 1, 2 or 3 (possibly as a string), got {props.get('rank')!r}")
        coords, gwhere = geometry(f, i, file, "Point")
        ra, dec = convert_point(coords, file, gwhere)
        label = {"text": props["name"], "ra_deg": ra, "dec_deg": dec}
        if fid in out:
            prev = out[fid]
            if prev["la"] != props["la"] or prev["rank"] != rank:
                fail(file, where, f"second feature with id {fid!r} disagrees on 'la' or 'rank' with the first")
            prev["labels"].append(label)
        else:
            out[fid] = {"name": props["name"], "la": props["la"], "rank": rank, "labels": [label]}
    return out


def ang_sep_deg(a, b):
    ra1, de1, ra2, de2 = (math.radians(v) for v in (a[0], a[1], b[0], b[1]))
    c = math.sin(de1) * math.sin(de2) + math.cos(de1) * math.cos(de2) * math.cos(ra1 - ra2)
    return math.degrees(math.acos(max(-1.0, min(1.0, c))))


def check_convention(lines):
    for cid, star, ra, dec in CHECK_STARS:
        pts = [p for line in lines.get(cid, []) for p in line]
        best = min((ang_sep_deg(p, (ra, dec)) for p in pts), default=float("inf"))
        if best > CHECK_TOLERANCE_DEG:
            raise InputError(
                f"{LINES_FILE}: coordinate convention check failed: no vertex of {cid} within "
                f"{CHECK_TOLERANCE_DEG} deg of {star} (RA {ra}, Dec {dec}); nearest is {best:.3f} deg")


def read_package_meta(pkg_dir):
    pj = os.path.join(pkg_dir, "package.json")
    meta = load_json(pj)
    for key in ("name", "version", "license"):
        if not isinstance(meta.get(key), str):
            fail("package.json", key, f"expected a string, got {meta.get(key)!r}")
    copyright_line = None
    lic = os.path.join(pkg_dir, "LICENSE")
    try:
        with open(lic, "r", encoding="utf-8") as f:
            for line in f:
                if line.strip().lower().startswith("copyright"):
                    copyright_line = line.strip()
                    break
    except OSError as e:
        raise InputError(f"LICENSE: cannot read {lic}: {e.strerror}")
    if copyright_line is None:
        fail("LICENSE", "(text)", "no line starting with 'Copyright'")
    return meta, copyright_line


def build(args):
    src = args.source
    meta, copyright_line = read_package_meta(os.path.join(src, os.pardir))
    paths = {n: os.path.join(src, n) for n in (LINES_FILE, NAMES_FILE, BOUNDS_FILE)}
    lines = read_lines(paths[LINES_FILE])
    names = read_names(paths[NAMES_FILE])
    bounds = read_bounds(paths[BOUNDS_FILE])

    for file, table in ((LINES_FILE, lines), (NAMES_FILE, names), (BOUNDS_FILE, bounds)):
        if len(table) != EXPECTED_COUNT:
            raise InputError(f"{file}: features[].id: expected {EXPECTED_COUNT} distinct constellations, "
                             f"found {len(table)}")
    for file, table in ((LINES_FILE, lines), (BOUNDS_FILE, bounds)):
        if set(table) != set(names):
            diff = sorted(set(table) ^ set(names))
            raise InputError(f"{file}: features[].id: ids differ from {NAMES_FILE}: {', '.join(diff)}")
    check_convention(lines)

    constellations, boundaries = [], []
    for cid in sorted(names):
        n = names[cid]
        # Split constellations (Serpens) are named by their Latin name; the parts stay in "labels".
        name = n["name"] if len(n["labels"]) == 1 else n["la"]
        first = n["labels"][0]
        constellations.append({
            "id": cid, "name": name, "rank": n["rank"],
            "label_ra_deg": first["ra_deg"], "label_dec_deg": first["dec_deg"],
            "labels": n["labels"], "lines": lines[cid],
        })
        boundaries.append({"id": cid, "polygons": bounds[cid]})

    inputs = [{"file": n, "sha256": sha256_of(paths[n])} for n in (LINES_FILE, NAMES_FILE, BOUNDS_FILE)]
    cmd = ["python3", "tools/convert_constellations.py", "--source", args.source, "--out", args.out]
    if args.boundaries_out:
        cmd += ["--boundaries-out", args.boundaries_out]
    if args.tarball:
        cmd += ["--tarball", args.tarball]
    provenance = {
        "source_package": meta["name"],
        "source_version": meta["version"],
        "source_registry": "npm",
        "source_homepage": meta.get("homepage", ""),
        "license": meta["license"],
        "copyright": copyright_line,
        "license_file": "data/sky/LICENSE.d3-celestial",
        "inputs": inputs,
        "converter": " ".join(cmd),
        "coordinate_conversion": "d3-celestial GeoJSON [lon, lat]: RA_deg = lon if lon >= 0 else lon + 360; "
                                 "Dec_deg = lat; rounded to 4 decimals",
        "serpens": "d3-celestial's two 'Ser' features (Serpens Caput, Serpens Cauda) merged into one entry",
    }
    if args.tarball:
        provenance["tarball"] = {"file": os.path.basename(args.tarball), "sha256": sha256_of(args.tarball)}
    return provenance, constellations, boundaries


def dumps(obj):
    return json.dumps(obj, ensure_ascii=False, separators=(",", ":"))


def write_doc(path, provenance, sections):
    """sections: list of (key, value); list values are written one element per line."""
    parts = ["{\n" + '"provenance": ' + json.dumps(provenance, ensure_ascii=False, indent=1)]
    for key, value in sections:
        if isinstance(value, list):
            body = ",\n".join(" " + dumps(v) for v in value)
            parts.append(f"{dumps(key)}: [\n{body}\n]")
        else:
            parts.append(f"{dumps(key)}: {dumps(value)}")
    text = ",\n".join(parts) + "\n}\n"
    json.loads(text)  # self-check: the hand-assembled document must parse
    d = os.path.dirname(path)
    if d:
        os.makedirs(d, exist_ok=True)
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)
    return len(text.encode("utf-8"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--source", required=True, help="d3-celestial's data/ directory (package.json in DIR/..)")
    ap.add_argument("--out", required=True, help="output JSON, e.g. data/sky/constellations.json")
    ap.add_argument("--boundaries-out", help="write boundaries to this separate file instead of --out")
    ap.add_argument("--tarball", help="the npm tarball the source came from (its sha256 is recorded)")
    args = ap.parse_args()
    try:
        provenance, constellations, boundaries = build(args)
    except InputError as e:
        print(f"convert_constellations: error: {e}", file=sys.stderr)
        return 1
    sections = [("frame", FRAME), ("constellations", constellations)]
    if args.boundaries_out:
        size_b = write_doc(args.boundaries_out, provenance, [("frame", FRAME), ("boundaries", boundaries)])
        print(f"wrote {args.boundaries_out}: {len(boundaries)} boundaries, {size_b} bytes")
    else:
        sections.append(("boundaries", boundaries))
    size = write_doc(args.out, provenance, sections)
    n_lines = sum(len(c["lines"]) for c in constellations)
    print(f"wrote {args.out}: {len(constellations)} constellations, {n_lines} lines, {size} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())

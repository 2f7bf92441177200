#!/usr/bin/env python3
"""Smoke test of benchmarks/frame_cost (no timing is judged): runs it at a tiny size and checks
that every stdout line is one JSON object with the fields BENCHMARKS.md and scripts/gpu_bench.sh
read, one line per view asked for, with consistent values.
    tests/test_frame_cost_output.py FRAME_COST [frame_cost arguments...]
The views, the size and whether a read-back was asked for are taken from the arguments.
"""
import json
import math
import subprocess
import sys


def arg_value(args, name, default):
    return args[args.index(name) + 1] if name in args else default


def check_line(line_no, line, size, read_back, overlays):
    where = f"frame_cost stdout line {line_no}"
    try:
        j = json.loads(line)
    except json.JSONDecodeError as err:
        sys.exit(f"{where}: not JSON ({err}): {line!r}")
    if not isinstance(j, dict):
        sys.exit(f"{where}: not a JSON object: {line!r}")
    for key, kind in (("view", str), ("size", int), ("frames", int), ("model", str), ("renderer", str),
                      ("read_back", bool), ("frame_ms", float), ("untimed_frame_ms", float),
                      ("trivial_ms", float), ("ratio", float), ("passes", dict), ("passes_ratio", dict),
                      ("read_back_ms", float), ("frame_min_ms", float), ("trivial_min_ms", float),
                      ("ratio_of_minima", float), ("frame_cpu_ms", float), ("trivial_cpu_ms", float),
                      ("ratio_cpu", float)):
        if key not in j:
            sys.exit(f"{where}: no \"{key}\" in {sorted(j)}")
        value = j[key]
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if not isinstance(value, kind) or (kind is int and isinstance(value, bool)):
            sys.exit(f"{where}: \"{key}\" is {value!r}, not a {kind.__name__}")
    if j["size"] != size:
        sys.exit(f"{where}: size {j['size']}, asked for {size}")
    if j["read_back"] != read_back:
        sys.exit(f"{where}: read_back {j['read_back']}, asked for {read_back}")
    for key in ("frame_ms", "untimed_frame_ms", "trivial_ms", "ratio", "frame_min_ms", "trivial_min_ms",
                "ratio_of_minima"):
        if not (math.isfinite(j[key]) and j[key] > 0):
            sys.exit(f"{where}: \"{key}\" is {j[key]}, not a positive number")
    if not math.isclose(j["ratio"], j["frame_ms"] / j["trivial_ms"], rel_tol=1e-9):
        sys.exit(f"{where}: ratio {j['ratio']} is not frame_ms / trivial_ms = {j['frame_ms'] / j['trivial_ms']}")
    if j["frame_min_ms"] > j["frame_ms"] or j["trivial_min_ms"] > j["trivial_ms"]:
        sys.exit(f"{where}: a minimum is above its median: {j}")
    passes = j["passes"]
    if not passes or set(passes) != set(j["passes_ratio"]):
        sys.exit(f"{where}: passes {sorted(passes)} and passes_ratio {sorted(j['passes_ratio'])} differ or are empty")
    for name, ms in passes.items():
        if not isinstance(ms, (int, float)) or isinstance(ms, bool) or not math.isfinite(ms) or ms < 0:
            sys.exit(f"{where}: pass \"{name}\" has {ms!r} ms")
    if j.get("overlays") != (overlays.split(",") if overlays else []):
        sys.exit(f"{where}: overlays {j.get('overlays')!r}, asked for {overlays}")
    # The earth-moon scene's passes; "overlays" only when they are shown.
    for name in ("stars", "sun and bodies", "atmosphere") + (("overlays",) if overlays else ()):
        if name not in passes:
            sys.exit(f"{where}: no pass \"{name}\" in {sorted(passes)}")
    total = sum(passes.values()) + j["read_back_ms"]
    if j["frame_ms"] < total * (1 - 1e-9):  # one frame: the medians are that frame's figures
        sys.exit(f"{where}: frame_ms {j['frame_ms']} is less than its passes and read-back ({total})")
    if read_back != (j["read_back_ms"] > 0):
        sys.exit(f"{where}: read_back_ms {j['read_back_ms']} with read_back {read_back}")
    return j["view"]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    command = sys.argv[1:]
    args = command[1:]
    views = arg_value(args, "--views", "day,sunset,orbit").split(",")
    size = int(arg_value(args, "--size", "1024"))
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300)
    sys.stderr.write(run.stderr)
    if run.returncode != 0:
        sys.exit(f"frame_cost exited with {run.returncode}")
    lines = [line for line in run.stdout.splitlines() if line.strip()]
    overlays = arg_value(args, "--overlays", "")
    seen = [check_line(n, line, size, "--read-back" in args, overlays) for n, line in enumerate(lines, 1)]
    if seen != views:
        sys.exit(f"frame_cost printed views {seen}, asked for {views}")
    print(f"frame_cost: {len(seen)} JSON lines with every field")


if __name__ == "__main__":
    main()
